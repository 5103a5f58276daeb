// `occsim view` as a user meets it: the executable does not link GLFW; without a display it says
// so in one line with exit code 2; and under a virtual X server (xvfb-run) a scripted session
// switches algorithms, shows node boxes and the bird's-eye view, records a flight, takes
// screenshots, resizes and closes with exit code 0, and the recorded flight replays headless to
// the very pixels the window showed.
#include <gtest/gtest.h>

#include "shell_command.h"
#include "sim/output/birds_eye.h"
#include "sim/scenario/scenario.h"

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

namespace occsim {
namespace {

using occsim::testing::Outcome;
using occsim::testing::shell;

const std::string kOccsim = OCCSIM_EXE;
const std::string kSmall = std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";

std::filesystem::path freshDir(const std::string& name) {
    // Per process: test suites of other checkouts may run at the same time on the same machine.
    const auto dir = std::filesystem::temp_directory_path() /
                     ("occsim-view-window-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

size_t lineCount(const std::string& s) {
    return static_cast<size_t>(std::count(s.begin(), s.end(), '\n'));
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

struct Image {
    int width = 0, height = 0;
    std::vector<Rgb> pixels;
    size_t count(Rgb c) const {
        return static_cast<size_t>(std::count(pixels.begin(), pixels.end(), c));
    }
};

Image readPng(const std::filesystem::path& file) {
    Image image;
    int channels = 0;
    unsigned char* data =
        stbi_load(file.string().c_str(), &image.width, &image.height, &channels, 3);
    if (!data) return image;
    for (int i = 0; i < image.width * image.height; ++i) {
        image.pixels.push_back({data[3 * i], data[3 * i + 1], data[3 * i + 2]});
    }
    stbi_image_free(data);
    return image;
}

TEST(ViewWindow, OccsimDoesNotLinkGlfw) {
    const Outcome o = shell("ldd " + kOccsim);
    ASSERT_EQ(o.exit_code, 0) << o.output;
    ASSERT_TRUE(contains(o.output, "libc.so")) << o.output;  // ldd really listed the libraries
    std::string lower = o.output;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    EXPECT_FALSE(contains(lower, "glfw")) << o.output;
}

TEST(ViewWindow, WithoutADisplayOneLineSuggestsTheHeadlessCommandsWithExitCode2) {
    const Outcome o = shell("env -u DISPLAY -u WAYLAND_DISPLAY " + kOccsim + " view " + kSmall);
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_TRUE(contains(o.output, "occsim run")) << o.output;
    EXPECT_TRUE(contains(o.output, "xvfb-run")) << o.output;
}

TEST(ViewWindow, BadScriptsAndSizesAreOneLineWithExitCode2BeforeAnyWindow) {
    const auto dir = freshDir("bad");
    const auto script = dir / "drive.txt";
    std::ofstream(script) << "wait 2\npress tabb\n";
    Outcome o = shell(kOccsim + " view " + kSmall + " --script " + script.string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_TRUE(contains(o.output, script.string() + ":2: unknown key 'tabb'")) << o.output;

    o = shell(kOccsim + " view " + kSmall + " --script " + (dir / "missing.txt").string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_TRUE(contains(o.output, "missing.txt: cannot open the script file")) << o.output;

    o = shell(kOccsim + " view " + kSmall + " --size 800by600");
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_TRUE(contains(o.output, "--size: expected WIDTHxHEIGHT")) << o.output;

    o = shell(kOccsim + " view " + kSmall + " --algo fastest");
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_TRUE(contains(o.output, "--algo: unknown algorithm 'fastest'")) << o.output;
    std::filesystem::remove_all(dir);
}

// The session: watch CHC with boxes, the bird's-eye view and ground truth in a 640 x 480 window;
// switch to frustum culling; shrink the window to the scenario's viewport (200 x 150) so that the
// flight's last frame can be compared with a headless capture pixel for pixel; record a short
// flight (12 frames) and take a screenshot of its last frame with the panel off; stop; resize;
// screenshot again. A screenshot shows the frame after the input before it, hence the waits.
constexpr const char* kSession = R"(# scripted viewer session (tests/system/test_view_window.cpp)
wait 3
press 4            # statistical+
press b            # node boxes
press m            # bird's-eye inset
press g            # ground truth
wait 3
press p            # screenshot 1
wait 1
press 1            # vfc: its frames are the same in the window and in a headless run
press b
press m
resize 200 150
wheel 2
wait 2
press r            # record: the world restarts at frame 0, the camera flies from here
hold w 6
drag 40 -15
hold d 4
wait 2
press space        # pause on the last recorded frame
press o            # panel off
press p            # screenshot 2
wait 1
press r            # stop: writes the recorded scenario
press o
press space
resize 320 240
wait 3
press p            # screenshot 3, at the new size
wait 1
)";

constexpr uint32_t kRecordedFrames = 12;  // hold w 6 + hold d 4 + wait 2

bool haveXvfbRun() { return shell("command -v xvfb-run").exit_code == 0; }

TEST(ViewWindow, AScriptedSessionUnderXvfbSavesScreenshotsAndAFlightThatReplaysHeadless) {
    if (!haveXvfbRun())
        GTEST_SKIP() << "xvfb-run is not installed (Debian: xvfb xauth); the window test needs it";
    const auto dir = freshDir("session");
    const auto script = dir / "session.txt";
    std::ofstream(script) << kSession;
    const auto out = dir / "out";
    const Outcome o =
        shell("xvfb-run -a -s '-screen 0 1280x1024x24' " + kOccsim + " view " + kSmall +
              " --size 640x480 --script " + script.string() + " --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_TRUE(contains(o.output, "recorded: ")) << o.output;

    // Screenshot 1 shows the scene with the boxes in the colours of what CHC did.
    const Image shot = readPng(out / "screenshot-001.png");
    ASSERT_EQ(shot.width, 640);
    ASSERT_EQ(shot.height, 480);
    std::set<std::tuple<uint8_t, uint8_t, uint8_t>> colours;
    for (const Rgb& p : shot.pixels) colours.insert({p.r, p.g, p.b});
    EXPECT_GT(colours.size(), 500u) << "a blank or flat picture";
    EXPECT_GT(shot.count(nodeClassColour(NodeClass::DrawnAfterQuery)), 20u);
    EXPECT_GT(shot.count(nodeClassColour(NodeClass::OcclusionCulled)) +
                  shot.count(nodeClassColour(NodeClass::DrawnWithoutQuery)),
              10u);
    EXPECT_GT(shot.count(kDrawnObjectColour), 10u) << "the bird's-eye inset";

    // The recorded flight is a scenario that run accepts, keyed at every recorded frame...
    const auto recorded = out / "teapots-small-recorded-001.json";
    ASSERT_TRUE(std::filesystem::exists(recorded)) << o.output;
    const Scenario flight = parseScenarioFile(recorded);
    EXPECT_EQ(flight.frames, kRecordedFrames);
    EXPECT_EQ(flight.camera.keyframes.size(), kRecordedFrames);
    const auto run_dir = dir / "replay";
    const Outcome run = shell(kOccsim + " run " + recorded.string() + " --algo vfc --capture " +
                              std::to_string(kRecordedFrames - 1) + " --out " + run_dir.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;

    // ... and replays the flown frames: its last frame is what the window showed.
    const Image window = readPng(out / "screenshot-002.png");
    char capture[64];
    std::snprintf(capture, sizeof capture, "frame-%05u-vfc.png", kRecordedFrames - 1);
    const Image replay = readPng(run_dir / capture);
    ASSERT_EQ(window.width, 200);  // the window was shrunk to the viewport before recording
    ASSERT_EQ(window.width, replay.width);
    ASSERT_EQ(window.height, replay.height);
    size_t differing = 0;
    for (size_t i = 0; i < window.pixels.size(); ++i)
        differing += !(window.pixels[i] == replay.pixels[i]);
    EXPECT_LE(differing, window.pixels.size() / 1000) << "of " << window.pixels.size() << " pixels";

    // The window was resized.
    const Image resized = readPng(out / "screenshot-003.png");
    EXPECT_EQ(resized.width, 320);
    EXPECT_EQ(resized.height, 240);
    if (!HasFailure()) std::filesystem::remove_all(dir);  // kept for a look when something failed
}

}  // namespace
}  // namespace occsim
