// The viewer's parts that need no window: scripted input, the flying camera, the key table, the
// text panel and recorded flights as scenario files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "occsim/culling/registry/registry.h"
#include "render/window_events.h"
#include "sim/view/fly_camera.h"
#include "sim/view/hud.h"
#include "sim/view/key_bindings.h"
#include "sim/view/node_boxes.h"
#include "sim/view/recorded_scenario.h"
#include "sim/view/view_script.h"

namespace occsim {
namespace {

const std::filesystem::path kScenarios = std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios";

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::filesystem::path freshDir(const std::string& name) {
    // Per process: test suites of other checkouts may run at the same time on the same machine.
    const auto dir = std::filesystem::temp_directory_path() /
                     ("occsim-view-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    return dir;
}

std::string scriptError(const std::string& text) {
    try {
        parseViewScript(text, "drive.txt");
    } catch (const ScriptError& e) {
        return e.what();
    }
    return "(no error)";
}

// ---- scripts -------------------------------------------------------------------------------

TEST(ViewScript, MistakesNameTheFileTheLineAndWhatWasExpected) {
    EXPECT_EQ(scriptError("wait 2\n\n  prss b\n"),
              "drive.txt:3: unknown command 'prss'; expected one of: wait, press, down, up, hold, "
              "drag, wheel, resize, quit");
    const std::string bad_key = scriptError("press shift+tabb");
    EXPECT_EQ(bad_key.rfind("drive.txt:1: unknown key 'tabb'; expected a letter, a digit", 0), 0u)
        << bad_key;
    EXPECT_EQ(scriptError("# set-up\nwait 0"),
              "drive.txt:2: wait FRAMES: expected an integer in [1, 1000000], got '0'");
    EXPECT_EQ(scriptError("hold w"),
              "drive.txt:1: 'hold' takes 2 arguments (hold KEY FRAMES), got 1");
    EXPECT_EQ(scriptError("resize 800 x"),
              "drive.txt:1: resize HEIGHT: expected an integer in [16, 8192], got 'x'");
    EXPECT_EQ(scriptError("wheel 2.5"),
              "drive.txt:1: wheel NOTCHES: expected an integer in [-100, 100], got '2.5'");
    EXPECT_EQ(scriptError("quit now"), "drive.txt:1: 'quit' takes 0 arguments (quit), got 1");
}

TEST(ViewScript, AMissingFileIsNamed) {
    try {
        readViewScript("/no/such/script.txt");
        FAIL() << "no error";
    } catch (const ScriptError& e) {
        EXPECT_EQ(std::string(e.what()), "/no/such/script.txt: cannot open the script file");
    }
}

// What each frame of a played script delivers.
std::vector<std::string> playAll(const std::string& text) {
    ScriptPlayer player(parseViewScript(text, "s.txt"));
    std::vector<std::string> frames;
    for (int guard = 0; guard < 1000; ++guard) {
        const ScriptPlayer::FrameInput in = player.next();
        std::string f;
        for (const WindowEvent& e : in.events) {
            switch (e.type) {
                case WindowEvent::Type::KeyDown:
                    f += "+" + std::string(e.key) + " ";
                    break;
                case WindowEvent::Type::KeyUp:
                    f += "-" + std::string(e.key) + " ";
                    break;
                case WindowEvent::Type::MouseDown:
                    f += "mouse+ ";
                    break;
                case WindowEvent::Type::MouseUp:
                    f += "mouse- ";
                    break;
                case WindowEvent::Type::CursorMove:
                    f += "at(" + std::to_string(int(e.x)) + "," + std::to_string(int(e.y)) + ") ";
                    break;
                case WindowEvent::Type::Scroll:
                    f += "wheel(" + std::to_string(int(e.y)) + ") ";
                    break;
                default:
                    f += "? ";
                    break;
            }
        }
        if (in.resize)
            f += "resize(" + std::to_string(in.resize->first) + "x" +
                 std::to_string(in.resize->second) + ") ";
        if (in.quit) f += "quit";
        frames.push_back(f);
        if (in.quit) break;
    }
    return frames;
}

TEST(ViewScript, InputAppliesBeforeTheNextFrameAndWaitsAndHoldsCountFrames) {
    const std::vector<std::string> frames = playAll(
        "press b   # boxes\nwait 2\nhold w 3\npress shift+tab\ndrag 10 -5\nwheel -2\nresize 320 "
        "200\n");
    const std::vector<std::string> expected = {
        "+b -b ",  // press, then the first of the two waited frames
        "",
        "+w ",  // held for three frames
        "",
        "",
        "-w +shift +tab -tab -shift at(100,100) mouse+ at(110,95) mouse- wheel(-2) resize(320x200) "
        "quit",
    };
    EXPECT_EQ(frames, expected);
}

TEST(ViewScript, QuitEndsThePlayEvenWithLinesLeft) {
    EXPECT_EQ(playAll("wait 1\nquit\npress b\n"), (std::vector<std::string>{"", "quit"}));
    EXPECT_EQ(playAll(""), (std::vector<std::string>{"quit"}));
}

// ---- keys ----------------------------------------------------------------------------------

TEST(ViewKeys, EveryActionKeyIsAKeyAWindowReportsAndNoKeyDoesTwoThings) {
    std::set<std::string> keys;
    for (const KeyBinding& b : actionKeys()) {
        if (b.keys == "1-9") continue;
        EXPECT_FALSE(findKeyName(b.keys).empty()) << b.keys;
        EXPECT_TRUE(keys.insert(std::string(b.keys)).second) << b.keys << " is bound twice";
        uint32_t index = 0;
        EXPECT_EQ(actionForKey(b.keys, &index), b.action) << b.keys;
    }
    // The flying keys act while held; an action on one of them would fire on every flight.
    for (const char* fly : {"w", "a", "s", "d", "e", "q", "shift", "up", "down", "left", "right"}) {
        EXPECT_EQ(keys.count(fly), 0u) << fly;
    }
    uint32_t index = 99;
    EXPECT_EQ(actionForKey("3", &index), ViewAction::SelectAlgorithm);
    EXPECT_EQ(index, 2u);
    EXPECT_EQ(actionForKey("w", &index), ViewAction::None);
}

// ---- the flying camera ---------------------------------------------------------------------

TEST(FlyCamera, TakesOverAPoseAndFliesAlongItsDirectionAtItsSpeed) {
    FlyCamera camera(2.0);
    camera.setPose({{1, 2, 3}, {1, 2, -7}});  // looking down -z
    const CameraPose pose = camera.pose();
    EXPECT_NEAR(glm::length(glm::normalize(pose.target - pose.position) - glm::dvec3(0, 0, -1)),
                0.0, 1e-12);

    FlyInput forward;
    forward.forward = 1;
    camera.fly(forward, 1.5);
    EXPECT_NEAR(glm::length(camera.position() - glm::dvec3(1, 2, 0)), 0.0, 1e-12);

    FlyInput diagonal;  // no faster than straight on
    diagonal.forward = 1;
    diagonal.right = 1;
    diagonal.fast = true;
    const glm::dvec3 before = camera.position();
    camera.fly(diagonal, 0.5);
    EXPECT_NEAR(glm::length(camera.position() - before), 2.0 * FlyCamera::kFastFactor * 0.5, 1e-12);
    EXPECT_GT(camera.position().x, before.x);  // right of -z is +x
}

TEST(FlyCamera, DragsTurnRightAndDownAndPitchStopsShortOfVertical) {
    FlyCamera camera;
    camera.setPose({{0, 0, 0}, {0, 0, -1}});
    camera.look(90.0 / FlyCamera::kLookDegPerPixel, 0.0);  // a quarter turn right: +x
    EXPECT_NEAR(glm::length(camera.forward() - glm::dvec3(1, 0, 0)), 0.0, 1e-9);
    camera.look(0.0, 1e6);  // far down
    EXPECT_NEAR(glm::degrees(std::asin(camera.forward().y)), -FlyCamera::kMaxPitchDeg, 1e-9);
}

TEST(FlyCamera, TheWheelScalesTheSpeed) {
    FlyCamera camera(4.0);
    camera.changeSpeed(2);
    EXPECT_DOUBLE_EQ(camera.speed(), 4.0 * FlyCamera::kSpeedStep * FlyCamera::kSpeedStep);
    camera.changeSpeed(-2);
    EXPECT_DOUBLE_EQ(camera.speed(), 4.0);
}

// ---- the text panel ------------------------------------------------------------------------

TEST(ViewHud, ShowsTheAlgorithmAndTheFrameFiguresAndErrorOnlyWhenOn) {
    HudState s;
    s.algorithm = "chc++";
    s.algorithm_place = 5;
    s.algorithm_count = 7;
    s.frame = 12;
    s.time_s = 0.4;
    s.has_stats = true;
    s.stats.frame_ms = 12.346;
    s.stats.queries = 175;
    s.stats.triangles = 1054541;
    s.stats.error_pixels = 1234;
    s.stats.tie_pixels = 56;
    s.stats.missed_objects = 2;
    std::vector<std::string> lines = hudLines(s);
    ASSERT_GE(lines.size(), 2u);
    EXPECT_EQ(lines[0], "chc++ (5/7)   frame 12  0.40 s   path");
    EXPECT_EQ(lines[1], "frame time 12.35 ms   queries 175   triangles 1,054,541   error off (g)");
    s.error_on = true;
    s.flying = true;
    s.fly_speed_mps = 3.0;
    s.recording = true;
    s.recorded_frames = 9;
    lines = hudLines(s);
    EXPECT_EQ(lines[0], "chc++ (5/7)   frame 12  0.40 s   flying 3.0 m/s   rec 9 frames");
    EXPECT_EQ(lines[1],
              "frame time 12.35 ms   queries 175   triangles 1,054,541   error px 1,234   ties 56  "
              " missed 2");
}

// Every row of the panel, keys and legend included, lies inside the picture and apart from the
// others, in a 400-pixel-tall window wide enough for the large font and in narrower ones.
TEST(ViewHud, EveryRowFitsA400PixelTallWindow) {
    HudState s;
    s.algorithm = "statistical+";
    s.has_stats = true;
    s.message = "screenshot written: out/x.png";
    s.help = true;
    s.legend = true;
    const size_t rows = hudLines(s).size() + shownNodeBoxClasses().size();
    for (const auto& [w, h] : {std::pair{1200u, 400u}, std::pair{1000u, 400u},
                               std::pair{800u, 400u}, std::pair{1600u, 300u}}) {
        const HudLayout layout = layoutHud(w, h, s);
        ASSERT_EQ(layout.rows.size(), rows);
        const int text_h = RasterCanvas::textHeight(layout.scale);
        for (size_t i = 0; i < layout.rows.size(); ++i) {
            const HudRow& r = layout.rows[i];
            EXPECT_GE(r.y, 0) << w << "x" << h << " row " << i;
            EXPECT_LE(r.y + text_h, static_cast<int>(h)) << w << "x" << h << " row " << i;
            EXPECT_GE(r.x, 0) << w << "x" << h << " row " << i;
            EXPECT_LE(r.x + r.width, static_cast<int>(w)) << w << "x" << h << " row " << i;
            for (size_t j = 0; j < i; ++j) {
                const HudRow& o = layout.rows[j];
                const bool apart = r.x >= o.x + o.width || o.x >= r.x + r.width ||
                                   r.y >= o.y + text_h || o.y >= r.y + text_h;
                EXPECT_TRUE(apart) << w << "x" << h << " rows " << j << " and " << i;
            }
        }
        EXPECT_LE(layout.panel_height, static_cast<int>(h));
    }
}

// ---- docs/viewer.md follows the program's tables ------------------------------------------

// The keys table lists exactly the program's action keys; the digit keys name the algorithms in
// the program's order; every "press DIGIT  # name" in the docs presses that algorithm; --algo
// lists every built-in algorithm.
TEST(ViewDocs, TheKeysAndAlgorithmsOfViewerMdAreTheProgramsOwn) {
    const std::string doc = readText(std::filesystem::path(OCCSIM_SOURCE_DIR) / "docs/viewer.md");
    const size_t keys_at = doc.find("## Keys");
    ASSERT_NE(keys_at, std::string::npos);
    const std::string keys = doc.substr(keys_at, doc.find("Flying", keys_at) - keys_at);
    size_t rows = 0;
    for (size_t at = keys.find("\n| `"); at != std::string::npos; at = keys.find("\n| `", at + 1))
        ++rows;
    EXPECT_EQ(rows, actionKeys().size()) << keys;
    for (const KeyBinding& k : actionKeys()) {
        EXPECT_NE(keys.find("\n| `" + std::string(k.keys) + "` |"), std::string::npos) << k.keys;
    }
    const auto& all = cullerRows();
    std::string digits;
    for (size_t i = 0; i < all.size() && i < 9; ++i) {
        digits += (i ? ", `" : "`") + std::to_string(i + 1) + "` " + std::string(all[i]->name);
    }
    EXPECT_NE(keys.find(digits), std::string::npos) << "expected the digit keys as: " << digits;
    std::istringstream lines(doc);
    std::string line;
    size_t presses = 0;
    while (std::getline(lines, line)) {
        unsigned digit = 0;
        char name[64] = {};
        if (std::sscanf(line.c_str(), "press %u # %63[^: ]", &digit, name) == 2 && digit >= 1 &&
            digit <= all.size()) {
            EXPECT_EQ(std::string(name), all[digit - 1]->name) << line;
            ++presses;
        }
    }
    EXPECT_GT(presses, 0u) << "the session example presses an algorithm's digit";
    const size_t algo_at = doc.find("| `--algo NAME` |");
    ASSERT_NE(algo_at, std::string::npos);
    const std::string algo_row = doc.substr(algo_at, doc.find('\n', algo_at) - algo_at);
    for (const CullerRow* a : all) {
        EXPECT_NE(algo_row.find("`" + std::string(a->name) + "`"), std::string::npos) << a->name;
    }
}

// ---- recorded flights ----------------------------------------------------------------------

std::vector<CameraKeyframe> flight(size_t frames, double dt) {
    std::vector<CameraKeyframe> keys;
    for (size_t i = 0; i < frames; ++i) {
        const double t = static_cast<double>(i) * dt;
        keys.push_back(
            {t, {0.1 * double(i), 2.0, 5.0 - 0.3 * double(i)}, {0.1 * double(i), 1.5, -5.0}});
    }
    return keys;
}

TEST(RecordedScenario, IsTheLoadedScenarioWithTheFlownPathKeyedAtEveryFrame) {
    const auto file = kScenarios / "small/teapots-small.json";
    const std::string text = readText(file);
    const Scenario original = parseScenarioFile(file);
    const auto dir = freshDir("recorded");
    const auto out = dir / "teapots-small-recorded-001.json";
    const std::vector<CameraKeyframe> keys = flight(3, original.dt_s);
    writeRecordedScenario(text, original, keys, out);

    const Scenario recorded = parseScenarioFile(out);
    EXPECT_EQ(recorded.name, "teapots-small-recorded-001");
    EXPECT_EQ(recorded.frames, 3u);
    EXPECT_EQ(recorded.warmup_frames, 2u);  // 5 in the original, clamped below the frame count
    EXPECT_FALSE(recorded.camera.loop);
    ASSERT_EQ(recorded.camera.keyframes.size(), 3u);
    for (size_t i = 0; i < keys.size(); ++i) {
        // Exactly the times a run samples the path at (frame * dt), and the flown poses.
        EXPECT_EQ(recorded.camera.keyframes[i].time_s, static_cast<double>(i) * original.dt_s);
        EXPECT_EQ(recorded.camera.keyframes[i].position, keys[i].position);
        EXPECT_EQ(recorded.camera.keyframes[i].target, keys[i].target);
    }
    EXPECT_EQ(recorded.camera.fov_y_deg, original.camera.fov_y_deg);
    EXPECT_EQ(recorded.camera.near_m, original.camera.near_m);
    EXPECT_EQ(recorded.camera.far_m, original.camera.far_m);
    EXPECT_EQ(recorded.dt_s, original.dt_s);
    EXPECT_EQ(recorded.seed, original.seed);
    EXPECT_EQ(recorded.width, original.width);
    EXPECT_EQ(recorded.movers.size(), original.movers.size());
    EXPECT_EQ(recorded.algorithm, original.algorithm);
    // The old baseline pins the old path: the new scenario gets its own, beside it.
    ASSERT_TRUE(recorded.expect.has_value());
    EXPECT_EQ(recorded.expect->baseline, dir / "teapots-small-recorded-001.baseline.json");
    EXPECT_EQ(recorded.expect->algorithms, original.expect->algorithms);

    // The author's key order stays.
    const std::string written = readText(out);
    EXPECT_LT(written.find("\"format_version\""), written.find("\"name\""));
    EXPECT_LT(written.find("\"viewport\""), written.find("\"camera\""));
    EXPECT_LT(written.find("\"camera\""), written.find("\"scene\""));
    if (!HasFailure()) std::filesystem::remove_all(dir);
}

TEST(RecordedScenario, GltfPathsStillFindTheirModelsFromTheNewFolder) {
    const auto file = kScenarios / "gltf-house.json";
    const Scenario original = parseScenarioFile(file);
    const auto dir = freshDir("recorded-gltf") / "elsewhere";
    const auto out = dir / "house-flight.json";
    writeRecordedScenario(readText(file), original, flight(2, original.dt_s), out);

    const Scenario recorded = parseScenarioFile(out);  // checks that the model exists
    const auto& was = std::get<GltfSourceSpec>(original.sources[0].spec).path;
    const auto& now = std::get<GltfSourceSpec>(recorded.sources[0].spec).path;
    EXPECT_TRUE(std::filesystem::equivalent(was, now)) << was << " vs " << now;
    EXPECT_EQ(recorded.name, "house-flight");
    EXPECT_EQ(recorded.frames, 2u);
    EXPECT_EQ(recorded.warmup_frames, 1u);
    if (!HasFailure()) std::filesystem::remove_all(dir.parent_path());
}

TEST(RecordedScenario, ExpectedFramesAreClampedToTheFlight) {
    const std::string text = R"({
  "format_version": 1,
  "frames": 50,
  "camera": {"orbit": {"center": [0, 0, -30], "radius": 45, "period": 20}, "near": 0.5},
  "scene": {"sources": [{"type": "teapots", "count": 10}]},
  "expect": {"frames": 40, "baseline": "somewhere.baseline.json"}
})";
    const auto dir = freshDir("recorded-expect");
    const Scenario original = parseScenarioText(text, dir / "orbit.json");
    const std::string written =
        recordedScenarioText(text, original, flight(4, original.dt_s), dir / "flight.json");
    const Scenario recorded = parseScenarioText(written, dir / "flight.json");
    ASSERT_TRUE(recorded.expect.has_value());
    EXPECT_EQ(recorded.expect->frames, 4u);
    EXPECT_EQ(recorded.expect->baseline, dir / "flight.baseline.json");
    EXPECT_EQ(recorded.camera.near_m, 0.5);
    EXPECT_EQ(recorded.camera.keyframes.size(), 4u);
    EXPECT_EQ(written.find("orbit"), std::string::npos);
    EXPECT_EQ(written.find("\"name\""), std::string::npos);  // absent before: the file name says it
}

}  // namespace
}  // namespace occsim
