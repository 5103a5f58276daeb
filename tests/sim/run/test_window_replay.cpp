// The worst windows of a real run (EGL): the frame replayed for a window's picture is the frame
// the run measured, and a segment's summary in the run is summarize() over its frames, the same
// with segments or without.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "render/gl_renderer.h"
#include "sim/run/runner.h"
#include "sim/run/segment_summaries.h"
#include "sim/scenario/scenario.h"

namespace occsim {
namespace {

const std::filesystem::path kSmall =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json";

// VFC draws every object in the frustum: its colour buffer is what the camera sees, the picture
// the replay draws with no culling code. Each frame of VFC's is kept by the on_frame hook.
TEST(WindowReplay, TheReplayedFrameIsTheFrameTheRunRendered) {
    BenchOptions options;
    for (const char* name : {"vfc", "chc", "ideal"}) options.algorithms.push_back(findCuller(name));
    options.frames = 24;
    std::map<uint32_t, std::vector<uint8_t>> vfc_frames;
    options.on_frame = [&](const FrameEvent& e) {
        if (e.config.label == "vfc") e.renderer.readColor(vfc_frames[e.frame]);
    };
    std::map<uint32_t, std::vector<uint8_t>> replayed;
    options.on_window_frame = [&](const ReplayedFrame& f) { replayed[f.frame] = f.rgba; };
    const BenchResult result = runBenchmark(parseScenarioFile(kSmall), options);
    EXPECT_EQ(result.window_reference, "ideal");
    std::vector<uint32_t> wanted;
    for (const RunRecord& r : result.runs) {
        for (const WorstWindow& w : r.worst_windows) wanted.push_back(w.worst_frame);
    }
    ASSERT_FALSE(wanted.empty());
    EXPECT_EQ(result.costs.window_frames_replayed, replayed.size());
    for (uint32_t frame : wanted) {
        ASSERT_TRUE(replayed.count(frame)) << frame;
        const std::vector<uint8_t>& a = replayed[frame];
        const std::vector<uint8_t>& b = vfc_frames.at(frame);
        ASSERT_EQ(a.size(), b.size());
        size_t differ = 0;
        for (size_t i = 0; i < a.size(); i += 4)
            differ += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
        // The same objects drawn in another order may differ only where two lie at one depth.
        EXPECT_LE(differ, a.size() / 4 / 1000) << "frame " << frame << ": " << differ << " pixels";
    }
}

TEST(WindowReplay, ASegmentsSummaryInARunIsSummarizeOverItsFrames) {
    BenchOptions options;
    options.algorithms = {findCuller("vfc"), findCuller("statistical")};
    options.frames = 20;
    options.measure_error = true;
    options.latency = {true, 6};
    Segment s;
    s.name = "middle";
    s.first_frame = 3;
    s.end_frame = 15;
    options.segments = {s};
    const Scenario scenario = parseScenarioFile(kSmall);
    const BenchResult result = runBenchmark(scenario, options);
    ASSERT_EQ(result.metadata.segments.size(), 1u);
    for (const RunRecord& r : result.runs) {
        ASSERT_EQ(r.segments.size(), 1u);
        const RunSummary direct =
            summarize(r.summary.label, framesIn(r.frames, s), scenario.warmup_frames);
        EXPECT_EQ(r.segments[0].frames, 12u);
        EXPECT_EQ(r.segments[0].timed_frames, 10u);  // teapots-small: 5 warm-up frames
        EXPECT_DOUBLE_EQ(r.segments[0].frame_ms.mean, direct.frame_ms.mean);
        EXPECT_DOUBLE_EQ(r.segments[0].queries_mean, direct.queries_mean);
        EXPECT_EQ(r.segments[0].error_pixels_total, direct.error_pixels_total);
        EXPECT_EQ(r.segments[0].label, r.summary.label);
    }
}

}  // namespace
}  // namespace occsim
