// A segment's tallies (sim/run/segment_tallies.h): popping and answers counted only within it.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "synthetic_frames.h"

namespace occsim {
namespace {

using testing::segment;

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

}  // namespace
}  // namespace occsim
