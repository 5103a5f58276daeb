// The history of regression runs through the commands: another format version refused (one line,
// exit 2, nothing written), --fail-on-change failing on worse only, machines as separate series.
// The history and its report in process: tests/sim/regress/test_history.cpp and
// test_history_report.cpp.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "merge_commands.h"
#include "sim/regress/history_plot.h"
#include "sim/regress/result_files.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using namespace merge_files;

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
