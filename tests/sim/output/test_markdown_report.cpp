// report.md (sim/output/markdown_report.h): the header, the comparison table's rows, the picture
// links and how to read them.
#include <gtest/gtest.h>

#include <string>

#include "sample_runs.h"
#include "sim/output/fixed_text.h"
#include "sim/output/markdown_report.h"
#include "sim/output/report.h"

namespace occsim {
namespace {

using testing::sampleRuns;

// A name with a '|' (a glTF node may have one) stays inside its cell.
TEST(MarkdownReport, ACellEscapesTheBarThatWouldEndIt) {
    EXPECT_EQ(markdownCell("crate|2"), "crate\\|2");
    EXPECT_EQ(markdownCell("||"), "\\|\\|");
    EXPECT_EQ(markdownCell("plain"), "plain");
}

TEST(MarkdownReport, HasTheHeaderTheTableRowsThePictureLinksAndHowToRead) {
    BenchResult result;
    result.runs = sampleRuns();
    RunMetadata& c = result.metadata;
    c.scenario_name = "teapots-small";
    c.scenario_file = "scenarios/small/teapots-small.json";
    c.frames = 30;
    c.warmup_frames = 5;
    c.error_measured = true;
    c.hardware_threads = 2;
    c.renderer = "llvmpipe (test)";
    c.width = 200;
    c.height = 150;
    c.command_line = "occsim bench scenarios/small/teapots-small.json --error --plots";
    c.sweep = Sweep{"", "threshold", {0, 4}};
    ReportFiles files;
    files.plot_files = {"plot-frame-time.png", "plot-frame-time.svg", "plot-time-vs-error.png"};
    files.birds_eye_files = {"birds-eye-chc-frame-00020.png"};
    const std::string md = markdownReport(result, files);

    EXPECT_NE(md.find("# occsim bench: teapots-small"), std::string::npos);
    EXPECT_NE(md.find(c.command_line), std::string::npos);
    EXPECT_NE(md.find("2 hardware threads"), std::string::npos);
    EXPECT_NE(md.find("llvmpipe (test)"), std::string::npos);
    EXPECT_NE(md.find("threshold = 0, 4"), std::string::npos);
    EXPECT_NE(md.find("first 5 frames are warm-up"), std::string::npos);
    EXPECT_NE(md.find("Ground-truth rendering, PNG writing and statistics I/O"), std::string::npos);
    // The table: same columns as the text table, one row per configuration, Pareto marked.
    const ComparisonTable t = comparisonTable(result.runs);
    std::string header = "|";
    for (const auto& h : t.header) header += " " + h + " |";
    EXPECT_NE(md.find(header), std::string::npos) << md;
    EXPECT_NE(md.find("| vfc | 20.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| **statistical threshold=4** | 12.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| **chc** | 14.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| ideal | 6.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("1.67x"), std::string::npos) << "speedup of statistical over VFC";
    // Pictures: the PNGs as images, the SVG linked; only the files named.
    EXPECT_NE(md.find("![Frame time per frame](plot-frame-time.png)"), std::string::npos);
    EXPECT_NE(md.find("(plot-frame-time.svg)"), std::string::npos);
    EXPECT_NE(md.find("![Time against error](plot-time-vs-error.png)"), std::string::npos);
    EXPECT_EQ(md.find("plot-queries-triangles"), std::string::npos);
    EXPECT_NE(md.find("](birds-eye-chc-frame-00020.png)"), std::string::npos);
    EXPECT_NE(md.find("## How to read this"), std::string::npos);
    EXPECT_NE(md.find("popping"), std::string::npos);
}

}  // namespace
}  // namespace occsim
