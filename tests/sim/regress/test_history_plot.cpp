// The history report's picture (sim/regress/history_plot.h), read as SVG text: a panel per figure,
// one line per algorithm and series that never joins two series, a point per run, names escaped,
// and a scenario a run did not have left out of that run.
#include <gtest/gtest.h>

#include <string>

#include "merge_files.h"
#include "sim/regress/history_plot.h"

namespace occsim {
namespace {

using namespace merge_files;

size_t countOf(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

TEST(HistoryPlot, EachSeriesIsALineOfItsOwnWithAPointPerRun) {
    // Machine m three runs, machine n one: statistical and vfc in scenario s each get one line
    // per series and figure.
    HistoryAnalysis a = analyseHistory(
        {entry("2025-01-01T00:00:00Z", "m", 2.0), entry("2025-01-02T00:00:00Z", "m", 2.1),
         entry("2025-01-03T00:00:00Z", "m", 2.0), entry("2025-01-04T00:00:00Z", "n", 1.0)},
        windowOf(1));
    ASSERT_EQ(a.series.size(), 2u);
    const std::string svg = historySvg(a, "s");
    const size_t panels = historyFigures().size();
    EXPECT_EQ(countOf(svg, "<g class=\"panel\""), panels);
    EXPECT_EQ(countOf(svg, "<polyline class=\"line\""), panels * 2 * 2);
    EXPECT_EQ(countOf(svg, "data-algorithm=\"statistical\" data-series=\"1\""), panels);
    EXPECT_EQ(countOf(svg, "data-algorithm=\"statistical\" data-series=\"2\""), panels);
    EXPECT_EQ(countOf(svg, "<circle class=\"point\""), panels * 2 * 4) << "a point per run";
    EXPECT_NE(svg.find("s: 4 runs (x: run number; dash: series)"), std::string::npos);
    EXPECT_EQ(countOf(svg, "class=\"flagged\""), 0u);
    // Scenario t has only statistical: one algorithm, two series.
    EXPECT_EQ(countOf(historySvg(a, "t"), "<polyline class=\"line\""), panels * 2);
}

TEST(HistoryPlot, AnAlgorithmsNameIsEscaped) {
    HistoryEntry e = entry("2025-01-01T00:00:00Z", "m", 2.0);
    e.scenarios["s"]["a<b>&\"c\""] = e.scenarios["s"]["statistical"];
    const std::string svg = historySvg(analyseHistory({e}, windowOf(1)), "s");
    EXPECT_EQ(svg.find("a<b>"), std::string::npos);
    EXPECT_NE(svg.find("a&lt;b&gt;&amp;"), std::string::npos) << svg.substr(0, 400);
}

}  // namespace
}  // namespace occsim
