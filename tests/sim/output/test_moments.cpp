// The moments of a run on synthetic frames (no OpenGL): a segment's figures are the run's
// figures over its frames, warm-up left out of its timing; each configuration's worst windows
// against Ideal (VFC when no Ideal ran) are the planted ones; report.md and summary.json give both.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "sim/output/markdown_report.h"
#include "sim/output/moments.h"
#include "sim/output/report.h"
#include "sim/run/segment_summaries.h"
#include "sim/run/segment_tallies.h"
#include "sim/run/worst_windows.h"

namespace occsim {
namespace {

// `count` frames from 0, frame f taking ms(f) and drawing objects(f) objects of 100 triangles.
template <class Ms, class Objects>
std::vector<FrameStats> frames(uint32_t count, Ms ms, Objects objects) {
    std::vector<FrameStats> out(count);
    for (uint32_t f = 0; f < count; ++f) {
        out[f].frame = f;
        out[f].time_s = f / 30.0;
        out[f].frame_ms = ms(f);
        out[f].objects_drawn = objects(f);
        out[f].triangles = 100 * out[f].objects_drawn;
        out[f].queries = f % 3;
        out[f].error_pixels = f == 6 ? 40 : 0;
        out[f].tie_pixels = 0;
        out[f].stray_pixels = 0;
        out[f].missed_objects = f == 6 ? 2 : 0;
        out[f].tied_away_objects = 0;
        out[f].visible_objects = 5;
    }
    return out;
}

Segment segment(const std::string& name, uint32_t first, uint32_t end) {
    Segment s;
    s.name = name;
    s.first_frame = first;
    s.end_frame = end;
    s.origin = "scenario";
    return s;
}

TEST(SegmentSummary, IsTheRunsSummaryOverItsFramesWithWarmupLeftOutOfTiming) {
    const auto all = frames(
        20, [](uint32_t f) { return double(f); }, [](uint32_t) { return 4; });
    const Segment s = segment("early", 3, 8);
    const RunSummary seg = summarizeSegment("vfc", all, s, 5, nullptr, 0, true);
    EXPECT_EQ(seg.frames, 5u);
    EXPECT_EQ(seg.timed_frames, 3u);  // frames 5, 6, 7: 3 and 4 are warm-up
    EXPECT_DOUBLE_EQ(seg.frame_ms.mean, 6.0);
    EXPECT_DOUBLE_EQ(seg.frame_ms.max, 7.0);
    // Error counts every frame of the segment, warm-up included: frame 6's 40 pixels.
    EXPECT_EQ(seg.error_pixels_total, 40);
    EXPECT_EQ(seg.error_worst_frame, 6u);
    EXPECT_EQ(seg.missed_objects_total, 2);
    EXPECT_DOUBLE_EQ(seg.error_pixels_mean, 8.0);
    const RunSummary whole = summarize("vfc", all, 5);
    EXPECT_EQ(whole.timed_frames, 15u);
    EXPECT_NE(whole.frame_ms.mean, seg.frame_ms.mean);
    // Outside the segment: frame 6 is the only error, so a later segment has none.
    EXPECT_EQ(summarizeSegment("vfc", all, segment("late", 10, 20), 5, nullptr, 0, true)
                  .error_pixels_total,
              0);
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

TEST(SegmentTallies, CountPoppingAndAnswersOnlyWithinEachSegment) {
    SegmentTallies tallies;
    tallies.reset({segment("a", 2, 5), segment("b", 4, 9)}, 3);
    for (uint32_t f = 0; f < 10; ++f) {
        // Object 0 is missing on frames 1 to 6; object 1 on frame 8.
        tallies.addMissing(f, {uint8_t(f >= 1 && f <= 6), uint8_t(f == 8)});
        tallies.addLatencies(f, {f});
    }
    EXPECT_EQ(tallies.poppingRuns(0), std::vector<uint32_t>{3});  // frames 2 to 4
    std::vector<uint32_t> b = tallies.poppingRuns(1);
    std::sort(b.begin(), b.end());
    EXPECT_EQ(b, (std::vector<uint32_t>{1, 3}));  // object 0 on 4 to 6, object 1 on 8
    // Answers from the warm-up's end only: frames 3 and 4 in a, 4 to 8 in b.
    const std::vector<uint64_t>& a = tallies.answerLatencies(0);
    uint64_t answers = 0;
    for (uint64_t n : a) answers += n;
    EXPECT_EQ(answers, 2u);
    EXPECT_EQ(a.size(), 5u);
    EXPECT_EQ(a[3], 1u);
}

// ---- worst windows -------------------------------------------------------------------------

// Ideal at 2 ms; the culler at 2 ms except a planted window (frames 40 to 49 at 6 ms, frame 44 at
// 9 ms) and a smaller bump (frames 70 to 74 at 4 ms).
std::vector<FrameStats> plantedCuller() {
    return frames(
        100,
        [](uint32_t f) {
            if (f == 44) return 9.0;
            if (f >= 40 && f < 50) return 6.0;
            if (f >= 70 && f < 75) return 4.0;
            return 2.0;
        },
        [](uint32_t f) { return f >= 40 && f < 50 ? 30 : 5; });
}

std::vector<FrameStats> idealFrames() {
    return frames(
        100, [](uint32_t) { return 2.0; }, [](uint32_t) { return 3; });
}

TEST(WorstWindows, ThePlantedWindowIsFoundWithTheFiguresThatExplainIt) {
    const std::vector<WorstWindow> w = findWorstWindows(plantedCuller(), idealFrames(), 10);
    ASSERT_EQ(w.size(), 3u);
    EXPECT_EQ(w[0].first_frame, 40u);
    EXPECT_EQ(w[0].frames, kWorstWindowFrames);
    EXPECT_DOUBLE_EQ(w[0].ratio, (9.0 + 9 * 6.0) / 20.0);
    EXPECT_EQ(w[0].worst_frame, 44u);
    EXPECT_DOUBLE_EQ(w[0].worst_frame_ms, 9.0);
    EXPECT_DOUBLE_EQ(w[0].objects_mean, 30.0);
    EXPECT_DOUBLE_EQ(w[0].reference_objects_mean, 3.0);
    EXPECT_DOUBLE_EQ(w[0].triangles_mean, 3000.0);
    EXPECT_EQ(w[0].error_pixels, 0);
    // The second does not overlap the first: the bump, from the first window that holds it whole.
    EXPECT_EQ(w[1].first_frame, 65u);
    EXPECT_DOUBLE_EQ(w[1].ratio, 1.5);
    for (const WorstWindow& x : w) {
        EXPECT_TRUE(x.first_frame >= w[0].first_frame + 10 || x.first_frame + 10 <= 40 ||
                    &x == &w[0]);
    }
}

TEST(WorstWindows, WarmupFramesAreInNoWindowAndAShortRunIsOneWindow) {
    // A spike in the warm-up (frame 3) is never a moment.
    std::vector<FrameStats> culler = idealFrames();
    culler[3].frame_ms = 50.0;
    culler[60].frame_ms = 3.0;
    const std::vector<WorstWindow> w = findWorstWindows(culler, idealFrames(), 10, 10, 1);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].first_frame, 51u);  // the first window holding frame 60
    EXPECT_EQ(w[0].worst_frame, 60u);
    // Fewer timed frames than a window: one window of all of them.
    const std::vector<WorstWindow> short_run = findWorstWindows(
        std::vector<FrameStats>(culler.begin(), culler.begin() + 14), idealFrames(), 10);
    ASSERT_EQ(short_run.size(), 1u);
    EXPECT_EQ(short_run[0].first_frame, 10u);
    EXPECT_EQ(short_run[0].frames, 4u);
    EXPECT_TRUE(findWorstWindows(culler, idealFrames(), 100).empty());
}

RunRecord record(const char* algorithm, std::vector<FrameStats> f) {
    RunRecord r;
    r.algorithm = findCuller(algorithm);
    r.frames = std::move(f);
    r.summary = summarize(algorithm, r.frames, 10);
    return r;
}

TEST(WorstWindows, AreAgainstIdealWhenItRanElseAgainstVfcAndNoneForTheReference) {
    std::vector<RunRecord> runs = {record("vfc", idealFrames()),
                                   record("statistical", plantedCuller()),
                                   record("ideal", idealFrames())};
    EXPECT_EQ(markWorstWindows(runs, 10), 2);
    EXPECT_FALSE(runs[0].worst_windows.empty());
    EXPECT_EQ(runs[1].worst_windows.at(0).first_frame, 40u);
    EXPECT_TRUE(runs[2].worst_windows.empty());
    runs.pop_back();
    EXPECT_EQ(markWorstWindows(runs, 10), 0);
    EXPECT_TRUE(runs[0].worst_windows.empty());
    EXPECT_EQ(runs[1].worst_windows.at(0).first_frame, 40u);
    runs.erase(runs.begin());
    EXPECT_EQ(markWorstWindows(runs, 10), -1);
    EXPECT_TRUE(runs[0].worst_windows.empty());
}

TEST(WorstWindows, WithRepetitionsEachFrameIsItsMedianSoOneSlowRepetitionIsNoMoment) {
    RunRecord r = record("statistical", plantedCuller());
    std::vector<FrameStats> hiccup = idealFrames();
    for (uint32_t f = 20; f < 30; ++f) hiccup[f].frame_ms = 40.0;  // one repetition only
    r.later_repetitions = {hiccup, plantedCuller()};
    const std::vector<FrameStats> median = medianFrames(r);
    EXPECT_DOUBLE_EQ(median[25].frame_ms, 2.0);
    EXPECT_DOUBLE_EQ(median[44].frame_ms, 9.0);
    std::vector<RunRecord> runs = {record("ideal", idealFrames()), r};
    markWorstWindows(runs, 10);
    EXPECT_EQ(runs[1].worst_windows.at(0).first_frame, 40u);
}

// ---- the reports -------------------------------------------------------------------------

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
    files.window_pictures = {windowPictureName(44)};
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
    EXPECT_NE(md.find("![worst-window-frame-00044.png](worst-window-frame-00044.png)"),
              std::string::npos)
        << md;
    // Only the pictures that exist are linked.
    EXPECT_EQ(md.find("](worst-window-frame-00070.png)"), std::string::npos) << md;
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

}  // namespace
}  // namespace occsim
