// Each configuration's worst windows (sim/run/worst_windows.h) on synthetic frames: the planted
// window found with the figures that explain it, against Ideal when it ran (else VFC), warm-up in
// no window, each frame the median of its repetitions.
#include <gtest/gtest.h>

#include <vector>

#include "synthetic_frames.h"

namespace occsim {
namespace {

using testing::idealFrames;
using testing::plantedCuller;
using testing::record;

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

}  // namespace
}  // namespace occsim
