// The history of regression runs: an entry written and read back, another format version refused
// (one line, exit 2, nothing written), and what a history report plots and flags: an injected
// slowdown, runs within the spread, a failure only for worse, machines as separate series.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "merge_files.h"
#include "sim/regress/history_plot.h"
#include "sim/regress/result_files.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using namespace merge_files;

TEST(History, AnEntryReadsBackAsWritten) {
    const fs::path dir = historyOf("roundtrip", {entry("2025-01-01T00:00:00Z", "m", 2.5)});
    const auto runs = readHistory(dir);
    ASSERT_EQ(runs.size(), 1u);
    EXPECT_EQ(historyEntryJson(runs[0]), historyEntryJson(entry("2025-01-01T00:00:00Z", "m", 2.5)));
    EXPECT_EQ(runs[0].scenarios.at("s").at("statistical").speedup, 2.5);
}

TEST(History, AnEntryMadeNowRecordsMachineCommitAndFigures) {
    const Json summary =
        Json::parse(R"json({"machine": {"backend": "osmesa", "gl_renderer": "llvmpipe (LLVM 15)"},
        "algorithms": [{"configuration": "vfc", "speedup_over_vfc": 1.0, "queries_per_frame": 0,
                        "objects_per_frame": 100, "error": {"pixels_per_frame_mean": 0}},
                       {"configuration": "chc", "speedup_over_vfc": 1.8, "queries_per_frame": 12.5,
                        "objects_per_frame": 30, "error": {"pixels_per_frame_mean": 0.5}}]})json");
    const HistoryEntry e = historyEntryNow({{"s", summary}}, "abc123");
    EXPECT_EQ(e.commit, "abc123");
    EXPECT_EQ(e.backend, "osmesa");
    EXPECT_EQ(e.renderer, "llvmpipe (LLVM 15)");
    EXPECT_FALSE(e.hostname.empty());
    EXPECT_FALSE(e.cpu.empty());
    EXPECT_EQ(e.date.size(), 20u) << e.date;
    EXPECT_EQ(e.scenarios.at("s").at("chc").speedup, 1.8);
    EXPECT_EQ(e.scenarios.at("s").at("chc").queries, 12.5);
    EXPECT_EQ(e.scenarios.at("s").at("chc").error, 0.5);
}

TEST(History, AnotherFormatVersionIsRefusedOneLineExitTwoNothingWritten) {
    const fs::path dir = historyOf("version", {entry("2025-01-01T00:00:00Z", "m", 2.5)});
    std::string text = historyEntryJson(entry("2025-01-02T00:00:00Z", "m", 2.5));
    text.replace(text.find("\"version\": 1"), 12, "\"version\": 2");
    writeFile(dir / "v2.json", text);
    EXPECT_THROW(readHistory(dir), ResultFileError);
    const size_t files = std::distance(fs::directory_iterator(dir), fs::directory_iterator());
    const fs::path out = dir.parent_path() / "report";
    fs::create_directories(out);
    writeFile(out / "report.md", "earlier report\n");
    writeFile(out / ".occsim-run", "");  // an earlier report's folder, replaceable
    expectRefused("history " + dir.string() + " --out " + out.string(),
                  "v2.json: /version: history format version 2; this program reads version 1", out);
    // regress --history refuses before running anything: no result folder, no new entry.
    const fs::path regress_out = dir.parent_path() / "regress-out";
    expectRefused(std::string("regress ") + OCCSIM_SOURCE_DIR +
                      "/scenarios/small/teapots-small.json --out " + regress_out.string() +
                      " --history " + dir.string(),
                  "history format version 2", out);
    EXPECT_FALSE(fs::exists(regress_out));
    EXPECT_EQ(
        static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator())),
        files);
}

TEST(HistoryReport, ThreeRunsArePlottedAndAnInjectedSlowdownIsFlagged) {
    const fs::path dir = historyOf("slowdown", {entry("2025-01-01T00:00:00Z", "m", 2.00),
                                                entry("2025-01-02T00:00:00Z", "m", 2.05),
                                                entry("2025-01-03T00:00:00Z", "m", 1.40)});
    const HistoryAnalysis a = analyseHistory(readHistory(dir), windowOf(1));
    ASSERT_EQ(a.runs.size(), 3u);
    ASSERT_EQ(a.flagged.size(), 1u);
    EXPECT_EQ(a.flagged[0].scenario, "s");
    EXPECT_EQ(a.flagged[0].algorithm, "statistical");
    EXPECT_EQ(a.flagged[0].figure, "speedup over VFC");
    EXPECT_TRUE(a.flagged[0].worse);
    EXPECT_NE(a.flagged[0].text().find("2.050 -> 1.400"), std::string::npos) << a.flagged[0].text();

    const fs::path out = dir.parent_path() / "report";
    const auto files = writeHistoryReport(out, a, windowOf(1));
    EXPECT_EQ(files, (std::vector<std::string>{"history-s.svg", "history-t.svg", "report.md"}));
    const std::string md = readFile(out / "report.md");
    EXPECT_NE(md.find("- **s statistical: speedup over VFC 2.050 -> 1.400"), std::string::npos)
        << md;
    EXPECT_NE(md.find("![s](history-s.svg)"), std::string::npos) << md;
    const std::string svg = readFile(out / "history-s.svg");
    // Four panels, two algorithms (one line each) and three runs per line; the slowdown ringed.
    size_t lines = 0, points = 0, pos = 0;
    while ((pos = svg.find("<polyline class=\"line\"", pos)) != std::string::npos) ++lines, ++pos;
    pos = 0;
    while ((pos = svg.find("<circle class=\"point\"", pos)) != std::string::npos) ++points, ++pos;
    EXPECT_EQ(lines, 8u);
    EXPECT_EQ(points, 24u);
    EXPECT_EQ(svg.find("class=\"flagged\""), svg.rfind("class=\"flagged\"")) << "one ring";
    EXPECT_NE(svg.find("class=\"flagged\""), std::string::npos);
    EXPECT_NE(svg.find("run 3, statistical: 1.4"), std::string::npos);
}

TEST(HistoryReport, RunsWithinTheSpreadAreNotFlagged) {
    const fs::path dir = historyOf("steady", {entry("2025-01-01T00:00:00Z", "m", 2.00),
                                              entry("2025-01-02T00:00:00Z", "m", 2.05),
                                              entry("2025-01-03T00:00:00Z", "m", 2.02)});
    const HistoryAnalysis a = analyseHistory(readHistory(dir), windowOf(1));
    EXPECT_TRUE(a.flagged.empty()) << a.flagged.front().text();
    EXPECT_NE(
        historyMarkdown(a, windowOf(1)).find("## Changes beyond the run-to-run spread\n\nNone."),
        std::string::npos);
    // Too few runs for the window: said, not flagged.
    const HistoryAnalysis b = analyseHistory(readHistory(dir), windowOf(3));
    EXPECT_TRUE(b.flagged.empty());
    ASSERT_EQ(b.not_compared.size(), 1u);
    EXPECT_NE(b.not_compared[0].find("3 runs, 6 needed for a window of 3"), std::string::npos)
        << b.not_compared[0];
}

TEST(HistoryReport, FailOnChangeFailsOnWorseOnlyNeverOnBetter) {
    // A speedup that rose beyond the spread is flagged "better": printed, and exit 0.
    const fs::path dir = historyOf("faster", {entry("2025-01-01T00:00:00Z", "m", 2.00),
                                              entry("2025-01-02T00:00:00Z", "m", 2.05),
                                              entry("2025-01-03T00:00:00Z", "m", 2.90)});
    const HistoryAnalysis a = analyseHistory(readHistory(dir), windowOf(1));
    ASSERT_EQ(a.flagged.size(), 1u);
    EXPECT_FALSE(a.flagged[0].worse);
    EXPECT_FALSE(a.anyWorse());
    const std::string out = (dir.parent_path() / "r").string();
    const Command better =
        runOccsim("history " + dir.string() + " --out " + out + " --window 1 --fail-on-change");
    EXPECT_EQ(better.status, 0) << better.output;
    EXPECT_NE(better.output.find("changed: s statistical: speedup over VFC 2.050 -> 2.900 "
                                 "(+41.5%, better)"),
              std::string::npos)
        << better.output;
    // The same folder with a slowdown after it: worse, exit 1.
    appendHistory(dir, entry("2025-01-04T00:00:00Z", "m", 1.20));
    const HistoryAnalysis b = analyseHistory(readHistory(dir), windowOf(1));
    EXPECT_TRUE(b.anyWorse());
    const Command worse =
        runOccsim("history " + dir.string() + " --out " + out + " --window 1 --fail-on-change");
    EXPECT_EQ(worse.status, 1) << worse.output;
    EXPECT_NE(worse.output.find(", worse)"), std::string::npos) << worse.output;
}

TEST(HistoryReport, MachinesAreSeparateSeriesNeverMixed) {
    // Machine m is steady at 2.0; a slower machine n joins with 1.0. Mixed into one series that
    // would read as a slowdown.
    const fs::path dir = historyOf(
        "machines",
        {entry("2025-01-01T00:00:00Z", "m", 2.0), entry("2025-01-02T00:00:00Z", "m", 2.0),
         entry("2025-01-03T00:00:00Z", "m", 2.0), entry("2025-01-04T00:00:00Z", "n", 1.0)});
    const HistoryAnalysis a = analyseHistory(readHistory(dir), windowOf(1));
    EXPECT_EQ(a.series.size(), 2u);
    EXPECT_TRUE(a.flagged.empty()) << a.flagged.front().text();
    const std::string svg = historySvg(a, "s");
    EXPECT_NE(svg.find("data-algorithm=\"statistical\" data-series=\"2\""), std::string::npos);
    // Through the command: the same report, exit 0, and a flagged slowdown with --fail-on-change.
    const Command c = runOccsim("history " + dir.string() + " --out " +
                                (dir.parent_path() / "r").string() + " --window 1");
    EXPECT_EQ(c.status, 0) << c.output;
    EXPECT_NE(c.output.find("history: 4 runs, 2 series, 2 scenarios, 0 changes flagged"),
              std::string::npos)
        << c.output;
    appendHistory(dir, entry("2025-01-05T00:00:00Z", "m", 1.5));
    const Command d =
        runOccsim("history " + dir.string() + " --out " + (dir.parent_path() / "r").string() +
                  " --window 1 --fail-on-change");
    EXPECT_EQ(d.status, 1) << d.output;
    EXPECT_NE(d.output.find("changed: s statistical: speedup over VFC 2.000 -> 1.500"),
              std::string::npos)
        << d.output;
}

}  // namespace
}  // namespace occsim
