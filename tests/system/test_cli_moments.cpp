// The moments of a real run as the command line gives them: --segments and a scenario's segments
// in the console, summary.json and report.md, the worst windows with a picture of each worst
// frame; a bad segment is one line naming the flag or file, exit 2, before any work.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "shell_command.h"

namespace {

using occsim::testing::Outcome;
using occsim::testing::shell;

Outcome runOccsim(const std::string& args) { return shell(std::string(OCCSIM_EXE) + " " + args); }

const std::string kSmall = std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";

std::filesystem::path freshPath(const std::string& name) {
    const auto p = std::filesystem::temp_directory_path() /
                   ("occsim-cli-moments-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(p);
    return p;
}

std::string textOf(const std::filesystem::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

size_t lineCount(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

// teapots-small (dt 0.0333333, 5 warm-up frames) with one segment of its own.
std::filesystem::path segmentedScenario(const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    nlohmann::json s = nlohmann::json::parse(std::ifstream(kSmall));
    s.erase("expect");
    s["segments"] = nlohmann::json::parse(R"([{"name": "start", "from_frame": 0, "to_frame": 8}])");
    const auto file = dir / "segmented.json";
    std::ofstream(file) << s.dump(2);
    return file;
}

TEST(CliMoments, ABenchWithSegmentsGivesEveryFigurePerSegmentAndTheWorstWindows) {
    const auto dir = freshPath("bench");
    const auto out = dir / "out";
    const Outcome o = runOccsim("bench " + segmentedScenario(dir).string() +
                                " --algos vfc,chc,ideal --frames 24 --error --segments "
                                "turn=0.4:0.6,tail=f16:24 --out " +
                                out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    // The console: a table per segment, then one worst-window line per culler against Ideal.
    EXPECT_NE(o.output.find("segment start: frames 0 to 7, 0.000 to 0.267 s (8 frames, 3 timed; "
                            "5 warm-up, not timed)"),
              std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("segment turn: frames 12 to 17, 0.400 to 0.600 s (6 frames, 6 timed), "
                            "from --segments"),
              std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("segment tail: frames 16 to 23"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("worst windows against ideal (10 timed frames"), std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("\n  vfc  frames "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("\n  chc  frames "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("worst-window pictures: "), std::string::npos) << o.output;

    const nlohmann::json summary = nlohmann::json::parse(textOf(out / "summary.json"));
    const nlohmann::json& segments = summary["segments"];
    ASSERT_EQ(segments.size(), 3u) << segments.dump(2);
    EXPECT_EQ(segments[0]["name"], "start");
    EXPECT_EQ(segments[0]["origin"], "scenario");
    EXPECT_EQ(segments[1]["name"], "turn");
    EXPECT_EQ(segments[1]["first_frame"], 12);
    EXPECT_EQ(segments[1]["last_frame"], 17);
    EXPECT_EQ(segments[1]["origin"], "--segments");
    for (const nlohmann::json& s : segments) {
        ASSERT_EQ(s["algorithms"].size(), 3u);
        EXPECT_EQ(s["algorithms"][1]["configuration"], "chc");
        EXPECT_EQ(s["algorithms"][1]["frames"], s["frames"]);
        EXPECT_TRUE(s["algorithms"][1].contains("error"));
    }
    EXPECT_EQ(segments[0]["algorithms"][1]["timed_frames"], 3);
    EXPECT_TRUE(segments[1]["algorithms"][1].contains("ratio_to_ideal"));
    EXPECT_TRUE(segments[1]["algorithms"][1].contains("speedup_over_vfc"));
    const nlohmann::json& windows = summary["worst_windows"];
    EXPECT_EQ(windows["reference"], "ideal");
    ASSERT_EQ(windows["configurations"].size(), 2u);  // vfc and chc; not Ideal itself
    const nlohmann::json& chc = windows["configurations"][1];
    EXPECT_EQ(chc["configuration"], "chc");
    // 19 timed frames: one window of 10, then one more that does not overlap it.
    ASSERT_GE(chc["windows"].size(), 1u);
    EXPECT_GE(chc["windows"][0]["first_frame"].get<int>(), 5);

    const std::string md = textOf(out / "report.md");
    EXPECT_NE(md.find("## Segments"), std::string::npos) << md;
    EXPECT_NE(md.find("### turn: frames 12 to 17"), std::string::npos) << md;
    EXPECT_NE(md.find("## Worst windows"), std::string::npos) << md;
    const uint32_t worst = chc["windows"][0]["worst_frame"].get<uint32_t>();
    char picture[64];
    std::snprintf(picture, sizeof picture, "worst-window-chc-frame-%05u.png", worst);
    EXPECT_TRUE(std::filesystem::exists(out / picture)) << picture;
    EXPECT_NE(md.find(std::string("](") + picture + ")"), std::string::npos) << md;
    std::filesystem::remove_all(dir);
}

TEST(CliMoments, ABadSegmentIsOneLineNamingTheFlagOrFileWithExitCode2AndWritesNothing) {
    const auto dir = freshPath("bad");
    const auto scenario = segmentedScenario(dir);
    const auto out = dir / "out";
    const struct {
        std::string args, must_contain;
    } cases[] = {
        {"bench " + kSmall + " --segments corner=4.0",
         "--segments: 'corner=4.0': expected NAME=FROM:TO (seconds) or NAME=fFROM:TO (frames)"},
        {"bench " + kSmall + " --segments late=1.2:1.5",
         "--segments: 'late=1.2:1.5': expected a time <= 1.33333 s"},
        {"run " + kSmall + " --frames 10 --segments late=f8:12",
         "--segments: 'late=f8:12': expected a frame <= 10 (to_frame is exclusive"},
        {"bench " + kSmall + " --segments back=0.6:0.4",
         "--segments: 'back=0.6:0.4': expected TO after FROM"},
        {"bench " + kSmall + " --segments a=0:0.2,a=0.2:0.4", "'a=0.2:0.4': 'a' is given twice"},
        {"bench " + kSmall + " --segments =0:0.2", "expected a segment name"},
        {"bench " + scenario.string() + " --segments start=f1:2",
         "'start' already names a segment of the scenario"},
    };
    for (const auto& c : cases) {
        const Outcome o = runOccsim(c.args + " --out " + out.string());
        EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << c.args << ": " << o.output;
        EXPECT_NE(o.output.find(c.must_contain), std::string::npos) << c.args << ": " << o.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
    }
    // A segment of the file past its run: the file, the pointer, what was expected.
    nlohmann::json s = nlohmann::json::parse(std::ifstream(scenario));
    s["segments"][0]["to_frame"] = 41;
    std::ofstream(dir / "past.json") << s.dump(2);
    const Outcome past =
        runOccsim("bench " + (dir / "past.json").string() + " --out " + out.string());
    EXPECT_EQ(past.exit_code, 2) << past.output;
    EXPECT_EQ(lineCount(past.output), 1u) << past.output;
    EXPECT_NE(past.output.find("past.json: /segments/0/to_frame: expected a frame <= 40"),
              std::string::npos)
        << past.output;
    std::filesystem::remove_all(dir);
}

// A shorter --frames cuts the scenario's segments and says so on stderr, instead of refusing.
TEST(CliMoments, AShorterRunCutsTheScenariosSegmentWithANote) {
    const auto dir = freshPath("cut");
    const Outcome o = runOccsim("bench " + segmentedScenario(dir).string() +
                                " --algos vfc --frames 6 --out " + (dir / "out").string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("note: segment 'start' (frames 0 to 7) cut to frame 5 by this run's 6 "
                            "frames (--frames)"),
              std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("segment start: frames 0 to 5"), std::string::npos) << o.output;
    std::filesystem::remove_all(dir);
}

}  // namespace
