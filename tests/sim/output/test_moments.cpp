// The moments of a run in report.md and summary.json (sim/output/moments.h), on synthetic frames
// (no OpenGL): each segment's speedups and ratios to Ideal, a segment inside the warm-up whose row
// says it is untimed, the worst windows with their pictures, and neither section without segments
// or a reference.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "sim/output/markdown_report.h"
#include "sim/output/moments.h"
#include "sim/output/report.h"
#include "sim/run/segment_summaries.h"
#include "synthetic_frames.h"

namespace occsim {
namespace {

using testing::frames;
using testing::idealFrames;
using testing::plantedCuller;
using testing::record;
using testing::segment;

BenchResult sampleResult() {
    BenchResult result;
    RunMetadata& m = result.metadata;
    m.scenario_name = "planted";
    m.frames = 100;
    m.warmup_frames = 10;
    m.dt_s = 1.0 / 30.0;
    m.segments = {segment("calm", 10, 30), segment("storm", 40, 50)};
    result.runs = {record("vfc", idealFrames()), record("statistical", plantedCuller()),
                   record("ideal", idealFrames())};
    for (RunRecord& r : result.runs) {
        for (const Segment& s : m.segments)
            r.segments.push_back(summarizeSegment(r.summary.label, r.frames, s, 10, nullptr, 0, 0));
    }
    result.window_reference = result.runs[size_t(markWorstWindows(result.runs, 10))].summary.label;
    return result;
}

TEST(MomentsReport, EachSegmentHasItsOwnSpeedupsAndRatiosToIdeal) {
    const BenchResult result = sampleResult();
    const std::vector<RunRecord> storm = segmentRuns(result, 1);
    EXPECT_DOUBLE_EQ(storm[1].summary.frame_ms.mean, (9.0 + 9 * 6.0) / 10.0);
    EXPECT_DOUBLE_EQ(ratioToOracle(storm, storm[1].summary), 6.3 / 2.0);
    EXPECT_DOUBLE_EQ(speedupOverReference(storm, storm[1].summary), 2.0 / 6.3);
    const std::vector<RunRecord> calm = segmentRuns(result, 0);
    EXPECT_DOUBLE_EQ(ratioToOracle(calm, calm[1].summary), 1.0);
    const nlohmann::json j = summaryJson(result);
    ASSERT_EQ(j["segments"].size(), 2u);
    EXPECT_EQ(j["segments"][1]["name"], "storm");
    EXPECT_EQ(j["segments"][1]["first_frame"], 40);
    EXPECT_EQ(j["segments"][1]["last_frame"], 49);
    EXPECT_DOUBLE_EQ(j["segments"][1]["algorithms"][1]["ratio_to_ideal"].get<double>(), 3.15);
    EXPECT_FALSE(j["segments"][1]["algorithms"][1].contains("options"));
    EXPECT_EQ(j["worst_windows"]["reference"], "ideal");
    EXPECT_EQ(j["worst_windows"]["window_frames"], kWorstWindowFrames);
    EXPECT_EQ(j["worst_windows"]["configurations"][1]["configuration"], "statistical");
    EXPECT_EQ(j["worst_windows"]["configurations"][1]["windows"][0]["first_frame"], 40);
    EXPECT_EQ(j["worst_windows"]["configurations"][1]["windows"][0]["worst_frame"], 44);
}

TEST(MomentsReport, ReportMdHasTheSegmentTablesAndTheWorstWindowsWithTheirPictures) {
    const BenchResult result = sampleResult();
    ReportFiles files;
    files.window_pictures = {windowPictureName("statistical", 44)};
    const std::string md = markdownReport(result, files);
    EXPECT_NE(md.find("## Segments"), std::string::npos) << md;
    EXPECT_NE(md.find("### storm: frames 40 to 49, 1.333 to 1.667 s (10 frames, 10 timed)"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| statistical | 6.30 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| statistical | 2.00 |"), std::string::npos) << md;  // calm
    EXPECT_NE(md.find("## Worst windows"), std::string::npos) << md;
    EXPECT_NE(md.find("- frames 40 to 49 (1.333 to 1.667 s): 3.15x ideal (6.30 / 2.00 ms per "
                      "frame); objects 30.0 / 3.0, triangles 3000 / 300 per frame"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("worst frame 44 (4.50x)"), std::string::npos) << md;
    EXPECT_NE(md.find("![worst-window-statistical-frame-00044.png]"
                      "(worst-window-statistical-frame-00044.png)"),
              std::string::npos)
        << md;
    // Only the pictures that exist are linked.
    EXPECT_EQ(md.find("-frame-00070.png)"), std::string::npos) << md;
    // A configuration's name is kept readable in its pictures' names.
    EXPECT_EQ(windowPictureName("statistical+ base_time=0.5", 3),
              "worst-window-statistical+_base_time_0.5-frame-00003.png");
    const std::string console = worstWindowsText(result, true);
    EXPECT_NE(console.find("worst windows against ideal (10 timed frames"), std::string::npos)
        << console;
    EXPECT_NE(console.find("  statistical  frames 40 to 49"), std::string::npos) << console;
    // By default briefly, in lines that fit 100 columns.
    const std::string brief = worstWindowsText(result);
    EXPECT_NE(brief.find("  statistical  frames 40-49: 3.15x, 6.3 / 2.0 ms, 30 / 3 objects"),
              std::string::npos)
        << brief;
    EXPECT_NE(brief.find("worst frame 44 (4.50x)"), std::string::npos) << brief;
    std::istringstream lines(brief);
    for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 100u) << line;
    EXPECT_NE(segmentTablesText(result).find("segment storm: frames 40 to 49"), std::string::npos);
}

TEST(MomentsReport, WithoutSegmentsOrAReferenceTheSectionsAreAbsent) {
    BenchResult result = sampleResult();
    result.metadata.segments.clear();
    for (RunRecord& r : result.runs) r.worst_windows.clear();
    result.window_reference.clear();
    const std::string md = markdownReport(result, {});
    EXPECT_EQ(md.find("## Segments"), std::string::npos);
    EXPECT_EQ(md.find("## Worst windows"), std::string::npos);
    EXPECT_EQ(segmentTablesText(result), "");
    EXPECT_EQ(worstWindowsText(result), "");
    EXPECT_TRUE(summaryJson(result)["segments"].empty());
    EXPECT_TRUE(summaryJson(result)["worst_windows"].is_null());
}

TEST(SegmentSummary, ASegmentInsideTheWarmupIsNotTimedAndItsRowSaysSo) {
    RunRecord r;
    r.algorithm = findCuller("vfc");
    r.frames = frames(
        20, [](uint32_t) { return 2.0; }, [](uint32_t) { return 4; });
    r.summary = summarize("vfc", r.frames, 5);
    r.segments = {summarizeSegment("vfc", r.frames, segment("start", 0, 4), 5, nullptr, 0, false)};
    EXPECT_EQ(r.segments[0].timed_frames, 0u);
    BenchResult result;
    result.metadata.segments = {segment("start", 0, 4)};
    result.metadata.warmup_frames = 5;
    result.metadata.dt_s = 1.0 / 30.0;
    result.runs = {r};
    const ComparisonTable t = comparisonTable(segmentRuns(result, 0));
    ASSERT_EQ(t.rows.size(), 1u);
    EXPECT_EQ(t.rows[0][1], "not timed");
    EXPECT_NE(
        segmentHeading(result.metadata.segments[0], result.metadata).find("0 timed; 4 warm-up"),
        std::string::npos)
        << segmentHeading(result.metadata.segments[0], result.metadata);
}

}  // namespace
}  // namespace occsim
