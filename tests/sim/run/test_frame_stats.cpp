// A run's figures from its frames (sim/run/frame_stats.h): the distribution, the Pareto front,
// popping, and the summaries of repetitions (medians, the spread of the mean, error summed).
#include <gtest/gtest.h>

#include "sim/run/shared_world.h"

namespace occsim {
namespace {

TEST(Distribution, MeanMedianAndNearestRankP95) {
    std::vector<double> v;
    for (int i = 1; i <= 100; ++i) v.push_back(i);
    const Distribution d = distributionOf(v);
    EXPECT_DOUBLE_EQ(d.mean, 50.5);
    EXPECT_DOUBLE_EQ(d.median, 50.5);
    EXPECT_DOUBLE_EQ(d.p95, 95.0);
    EXPECT_DOUBLE_EQ(d.min, 1.0);
    EXPECT_DOUBLE_EQ(d.max, 100.0);
    EXPECT_DOUBLE_EQ(distributionOf({3.0}).p95, 3.0);
}

TEST(Pareto, KeepsExactlyThePointsNoOtherPointBeatsInTimeAndError) {
    // (time, error): b dominates d; c and e tie in time, e has less error; a is fastest.
    const std::vector<double> time = {1.0, 2.0, 3.0, 2.5, 3.0, 5.0};
    const std::vector<double> error = {9.0, 4.0, 3.0, 4.0, 1.0, 0.0};
    const std::vector<bool> front = paretoFront(time, error);
    EXPECT_EQ(front, (std::vector<bool>{true, true, false, false, true, true}));
    EXPECT_EQ(paretoFront({1.0, 1.0}, {2.0, 2.0}), (std::vector<bool>{true, true}))
        << "identical points do not dominate each other";
}

TEST(Popping, CountsConsecutiveMissingFramesPerObject) {
    PoppingCounter counter;
    // Object 0 misses frames 1-3, object 1 misses frame 0 and frames 2, object 2 misses 4-5 (open).
    const std::vector<std::vector<uint8_t>> frames = {{0, 1, 0}, {1, 0, 0}, {1, 1, 0},
                                                      {1, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    for (const auto& f : frames) counter.addFrame(f);
    std::vector<uint32_t> runs = counter.runs();
    std::sort(runs.begin(), runs.end());
    EXPECT_EQ(runs, (std::vector<uint32_t>{1, 1, 2, 3}));
    RunSummary s;
    addPopping(s, runs);
    EXPECT_EQ(s.popping_events, 4u);
    EXPECT_EQ(s.popping_max_frames, 3u);
    EXPECT_DOUBLE_EQ(s.popping_mean_frames, 7.0 / 4.0);
}

TEST(Summary, ErrorPerFrameMeanAndP99) {
    std::vector<FrameStats> frames(100);
    for (uint32_t i = 0; i < 100; ++i) {
        frames[i].frame = i;
        frames[i].error_pixels = i;  // 0..99
        frames[i].missed_objects = 0;
    }
    const RunSummary s = summarize("x", frames, 0);
    EXPECT_DOUBLE_EQ(s.error_pixels_mean, 49.5);
    EXPECT_DOUBLE_EQ(s.error_pixels_p99, 98.0);
    EXPECT_EQ(s.error_pixels_worst, 99);
}

TEST(Summary, RepetitionsGiveMediansAndTheSpreadOfTheMean) {
    RunSummary a, b, c;
    a.frame_ms.mean = 10, b.frame_ms.mean = 30, c.frame_ms.mean = 12;
    a.queries_mean = 5, b.queries_mean = 5, c.queries_mean = 8;
    const RunSummary m = aggregateRepetitions({a, b, c});
    EXPECT_EQ(m.repetitions, 3u);
    EXPECT_DOUBLE_EQ(m.frame_ms.mean, 12.0);
    EXPECT_DOUBLE_EQ(m.frame_ms_mean_min, 10.0);
    EXPECT_DOUBLE_EQ(m.frame_ms_mean_max, 30.0);
    EXPECT_DOUBLE_EQ(m.queries_mean, 5.0);
}

// Issue 40's case: async with (0 px, 0 missed), (0, 0) and (2 px, 1 missed) over three
// repetitions. A median would report it exact; the counts are summed, the worst kept.
TEST(Summary, RepetitionsSumErrorCountsInsteadOfTakingTheirMedian) {
    RunSummary clean, miss;
    clean.frames = miss.frames = 120;
    clean.frame_ms.mean = 10, miss.frame_ms.mean = 11;
    miss.error_pixels_total = 2;
    miss.missed_objects_total = 1;
    miss.frames_with_error = 1;
    miss.error_pixels_worst = 2;
    miss.error_worst_frame = 57;
    miss.error_pixels_mean = 2.0 / 120.0;
    miss.error_pixels_p99 = 0;
    miss.tie_pixels_total = 4;
    miss.popping_events = 1;
    miss.popping_mean_frames = 1;
    miss.popping_max_frames = 1;
    const RunSummary m = aggregateRepetitions({clean, clean, miss});
    EXPECT_EQ(m.error_pixels_total, 2);
    EXPECT_EQ(m.missed_objects_total, 1);
    EXPECT_EQ(m.frames_with_error, 1u);
    EXPECT_EQ(m.error_pixels_worst, 2);
    EXPECT_EQ(m.error_worst_frame, 57u);
    EXPECT_EQ(m.tie_pixels_total, 4);
    EXPECT_EQ(m.popping_events, 1u);
    EXPECT_GT(m.error_pixels_mean, 0.0) << "a miss in one repetition keeps the mean above zero";
    EXPECT_DOUBLE_EQ(m.error_pixels_mean, 2.0 / 360.0);
    EXPECT_DOUBLE_EQ(m.frame_ms.mean, 10.0) << "times keep their median";
    // The same three ways round: a sum, whatever the order.
    EXPECT_EQ(aggregateRepetitions({miss, clean, miss}).missed_objects_total, 2);
}

// A Pareto mark decided by a difference below the run-to-run noise is a tie: with repetitions,
// two times whose ranges overlap are not told apart.
TEST(Summary, TheParetoFrontTiesTimesWhoseSpreadsOverlap) {
    // a: 10.0 ms [9.5-10.5], 0 error; b: 10.2 ms [9.8-10.6], 0 error: neither is faster.
    EXPECT_EQ(paretoFront({9.5, 9.8}, {10.5, 10.6}, {0.0, 0.0}), (std::vector<bool>{true, true}));
    // Apart beyond the spread, the slower one drops off.
    EXPECT_EQ(paretoFront({9.5, 11.0}, {10.5, 11.6}, {0.0, 0.0}), (std::vector<bool>{true, false}));
    // Tied on time, the one with less error dominates.
    EXPECT_EQ(paretoFront({9.5, 9.8}, {10.5, 10.6}, {0.1, 0.0}), (std::vector<bool>{false, true}));
    // One repetition: the means decide, as before.
    EXPECT_EQ(paretoFront({10.0, 10.2}, {0.0, 0.0}), (std::vector<bool>{true, false}));
}

TEST(Summary, TimingSkipsWarmupFramesButErrorCountsEveryFrame) {
    std::vector<FrameStats> frames(10);
    for (uint32_t i = 0; i < 10; ++i) {
        frames[i].frame = i;
        frames[i].frame_ms = i < 3 ? 1000.0 : 10.0;
        frames[i].error_pixels = i == 1 ? 7 : 0;
        frames[i].missed_objects = i == 1 ? 1 : 0;
    }
    const RunSummary s = summarize("x", frames, 3);
    EXPECT_EQ(s.timed_frames, 7u);
    EXPECT_DOUBLE_EQ(s.frame_ms.mean, 10.0);
    EXPECT_EQ(s.error_pixels_total, 7);
    EXPECT_EQ(s.error_worst_frame, 1u);
    EXPECT_EQ(s.frames_with_error, 1u);
}

TEST(FrameStats, AnswerLatencyRanksAreNearestRankOverTheHistogram) {
    RunSummary s;
    addAnswerLatencies(s, {0, 10, 0, 8, 2});  // 10 x 1, 8 x 3, 2 x 4
    EXPECT_EQ(s.answers, 20u);
    EXPECT_EQ(s.answer_latency_median, 1.0);  // rank 10
    EXPECT_EQ(s.answer_latency_p95, 4.0);     // rank 19
    addAnswerLatencies(s, {});
    EXPECT_EQ(s.answer_latency_median, -1.0);
    std::vector<uint32_t> frame = {7, 1, 3, 5};
    EXPECT_EQ(medianLatency(frame), 4.0);
}

}  // namespace
}  // namespace occsim
