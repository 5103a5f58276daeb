// Culling files beside a run: one overrides the scenario's options (a bad one is one line naming
// the file and pointer), a tuned file runs beside the defaults, a cost model changes only its
// own culler.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

using namespace occsim::cli_run;

namespace {

// --culling FILE: a scenario's culling section on its own (what occtune writes as tuned.json),
// read with the scenario parser's strict readers and applied over the scenario's.
TEST(Cli, CullingFileOverridesTheScenariosCullingOptions) {
    const auto dir = tempPath("culling");
    std::filesystem::create_directories(dir);
    const auto file = dir / "culling.json";
    std::ofstream(file)
        << R"({"format_version": 1, "culling": {"algorithm": "vfc", "statistical": {"base_time": 0.3}}})";
    // The scenario's algorithm is statistical; the file's wins.
    const Outcome o = runOccsim("run " + kSmall + " --frames 3 --culling " + file.string() +
                                " --out " + (dir / "run").string());
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("\nvfc "), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("statistical"), std::string::npos) << o.output;
    std::filesystem::remove_all(dir);
}

TEST(Cli, BadCullingFileIsOneLineNamingTheFileAndPointerWithExitCode2) {
    const auto dir = tempPath("bad-culling");
    std::filesystem::create_directories(dir);
    const struct {
        std::string contents, must_contain;
    } cases[] = {
        {R"({"format_version": 1, "culling": {"statistical": {"base_tme": 0.3}}})",
         "/culling/statistical/base_tme: unknown key 'base_tme'; did you mean 'base_time'?"},
        {R"({"format_version": 1, "culling": {"statistical": {"decay_b": 2}}})",
         "/culling/statistical/decay_b: expected a number in [0, 1], got 2"},
        {R"({"format_version": 1})", "missing required key 'culling'"},
        {R"({"format_version": 1, "culling": {}, "camera": {}})", "unknown key 'camera'"},
        {R"({"culling": {}})", "format_version"},
    };
    for (const auto& c : cases) {
        const auto file = dir / "culling.json";
        std::ofstream(file) << c.contents;
        for (const std::string& command :
             {"run " + kSmall, "bench " + kSmall, "regress " + kSmall}) {
            const Outcome o = runOccsim(command + " --culling " + file.string() + " --out " +
                                        (dir / "out").string());
            EXPECT_EQ(o.exit_code, 2) << command << " " << c.contents << ": " << o.output;
            EXPECT_EQ(lineCount(o.output), 1u) << command << ": " << o.output;
            EXPECT_NE(o.output.find(file.string()), std::string::npos) << o.output;
            EXPECT_NE(o.output.find(c.must_contain), std::string::npos) << o.output;
            EXPECT_FALSE(std::filesystem::exists(dir / "out")) << command;
        }
    }
    std::filesystem::remove_all(dir);
}

// --algos NAME,NAME@tuned.json: a tuned file's setting runs beside the culler's own, interleaved
// in one run, as a row of its own everywhere; a file that cannot be that is one line, exit 2.
TEST(Cli, ATunedFileRunsBesideTheDefaultsInterleavedAndLabelledApart) {
    const auto dir = tempPath("tuned-beside");
    std::filesystem::create_directories(dir);
    auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return (dir / name).string();
    };
    const std::string tuned =
        write("tuned.json", R"({"format_version": 1, "tuned_for": "statistical+", "culling": {
            "algorithm": "statistical+",
            "statistical+": {"queries_before_restart": 1, "ready_answers": true}}})");
    const auto out = dir / "out";
    const Outcome o =
        runOccsim("bench " + kSmall + " --algos statistical+,statistical+@" + tuned +
                  " --frames 8 --deterministic-latency 8 --quiet --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("\nstatistical+@tuned "), std::string::npos) << o.output;
    std::ifstream summary_in(out / "summary.json");
    const std::string summary{std::istreambuf_iterator<char>(summary_in),
                              std::istreambuf_iterator<char>()};
    EXPECT_NE(summary.find("\"configuration\": \"statistical+@tuned\""), std::string::npos);
    EXPECT_NE(summary.find("\"culling_file\": \"" + tuned + "\""), std::string::npos) << summary;
    EXPECT_NE(summary.find("\"queries_before_restart\": 1,"), std::string::npos) << summary;
    std::ifstream report_in(out / "report.md");
    const std::string report{std::istreambuf_iterator<char>(report_in),
                             std::istreambuf_iterator<char>()};
    EXPECT_NE(report.find("| statistical+@tuned |"), std::string::npos) << report;
    // frames.csv: both rows every frame, interleaved in one run; the tuned options decide
    // otherwise (another query count on some frame).
    std::ifstream csv(out / "frames.csv");
    std::map<std::string, std::vector<std::string>> queries;
    std::string line;
    std::getline(csv, line);
    while (std::getline(csv, line)) {
        std::vector<std::string> cells;
        std::stringstream cell(line);
        for (std::string c; std::getline(cell, c, ',');) cells.push_back(c);
        ASSERT_GT(cells.size(), 8u) << line;
        queries[cells[0]].push_back(cells[8]);
    }
    ASSERT_EQ(queries.size(), 2u);
    EXPECT_EQ(queries["statistical+"].size(), 8u);
    EXPECT_EQ(queries["statistical+@tuned"].size(), 8u);
    EXPECT_NE(queries["statistical+"], queries["statistical+@tuned"]);

    // Bad input: one line naming the flag and the file, exit 2, nothing written.
    const std::string other =
        write("other.json", R"({"format_version": 1, "tuned_for": "statistical", "culling": {
            "algorithm": "statistical", "statistical": {"base_time": 0.3}}})");
    const std::string broken = write("broken.json", R"({"format_version": 1, "culling": )");
    const struct {
        std::string entry, expected;
    } refused[] = {
        {"statistical+@" + (dir / "missing.json").string(), "missing.json: cannot open file"},
        {"statistical+@" + broken, "broken.json: "},
        {"statistical+@" + other, "other.json is a culling file for statistical, not statistical+"},
        {"statistical+@", "no file after '@'"},
        {"statistical+@" + tuned + ",statistical+@" + tuned,
         "'statistical+@tuned' is listed twice"},
    };
    for (const auto& r : refused) {
        const auto bad_out = dir / "bad-out";
        const Outcome bad = runOccsim("bench " + kSmall + " --algos " + r.entry +
                                      " --frames 2 --out " + bad_out.string());
        EXPECT_EQ(bad.exit_code, 2) << r.entry << ": " << bad.output;
        EXPECT_EQ(lineCount(bad.output), 1u) << bad.output;
        EXPECT_EQ(bad.output.rfind("occsim: --algos", 0), 0u) << bad.output;
        EXPECT_NE(bad.output.find(r.expected), std::string::npos) << bad.output;
        EXPECT_FALSE(std::filesystem::exists(bad_out)) << r.entry;
    }
    std::filesystem::remove_all(dir);
}

// A cost model a culling file gives for one culler (as tuned.json does) reaches that culler
// only: statistical+ keeps the reference figures of a deterministic run.
TEST(Cli, ACostModelForOneCullerChangesNoOther) {
    const auto dir = tempPath("scoped-cost");
    std::filesystem::create_directories(dir);
    const auto file = dir / "tuned.json";
    std::ofstream(file) << R"({"format_version": 1, "culling": {"algorithm": "statistical",
        "statistical": {"cost_model": true},
        "cost_model": {"query_box_ms": 0.5, "triangle_ms": 0.25, "draw_call_ms": 0.125, "cullers": ["statistical"]}}})";
    const auto out = dir / "out";
    const Outcome o = runOccsim("bench " + kSmall +
                                " --algos statistical,statistical+ --frames 2 "
                                "--deterministic-latency 4 --culling " +
                                file.string() + " --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    const size_t plus = json.find("\"configuration\": \"statistical+\"");
    const size_t paper = json.find("\"configuration\": \"statistical\"");
    ASSERT_NE(plus, std::string::npos) << json;
    ASSERT_NE(paper, std::string::npos) << json;
    // Each algorithm's object: from its start to the next configuration (or the end of the list).
    auto objectOf = [&](size_t at) {
        const size_t open = json.rfind("\n    {", at);
        return json.substr(open, json.find("\n    }", at) - open);
    };
    EXPECT_NE(objectOf(paper).find("\"query_box_ms\": 0.5"), std::string::npos) << objectOf(paper);
    EXPECT_NE(objectOf(plus).find("\"cost_model\": {"), std::string::npos) << objectOf(plus);
    EXPECT_EQ(objectOf(plus).find("\"query_box_ms\": 0.5"), std::string::npos) << objectOf(plus);
    std::filesystem::remove_all(dir);
}

}  // namespace
