// A segment's summary (sim/run/segment_summaries.h) on synthetic frames: the run's figures over its
// frames, warm-up left out of its timing.
#include <gtest/gtest.h>

#include <string>

#include "sim/run/segment_summaries.h"
#include "synthetic_frames.h"

namespace occsim {
namespace {

using testing::frames;
using testing::segment;

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

}  // namespace
}  // namespace occsim
