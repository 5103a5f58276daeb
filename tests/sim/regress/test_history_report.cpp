// What a history report (sim/regress/history_report.h) plots and flags: an injected slowdown
// flagged and ringed, runs within the run-to-run spread not flagged, too few runs for the window
// said. Machines as separate series and --fail-on-change through the command:
// tests/system/test_history.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "merge_files.h"
#include "sim/regress/history_report.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using namespace merge_files;

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

}  // namespace
}  // namespace occsim
