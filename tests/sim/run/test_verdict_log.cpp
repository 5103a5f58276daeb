// The objects a configuration missed and drew while hidden, frame by frame
// (sim/run/verdict_log.h): kept sparse, found again by frame, and under a budget that ends the
// log rather than leaving holes in it.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "sim/run/simulation.h"
#include "sim/run/verdict_log.h"

namespace occsim {
namespace {

std::vector<uint8_t> verdicts(std::initializer_list<ObjectVerdict> list) {
    std::vector<uint8_t> out;
    for (ObjectVerdict v : list) out.push_back(static_cast<uint8_t>(v));
    return out;
}

TEST(VerdictLog, KeepsWhatWasMissedAndDrawnWhileHiddenByFrame) {
    VerdictLog log(1 << 20);
    log.record(
        0, verdicts({ObjectVerdict::DrawnVisible, ObjectVerdict::Missed, ObjectVerdict::DrawnHidden,
                     ObjectVerdict::Culled, ObjectVerdict::Missed}));
    log.record(
        2, verdicts({ObjectVerdict::DrawnHidden, ObjectVerdict::DrawnVisible,
                     ObjectVerdict::DrawnVisible, ObjectVerdict::Culled, ObjectVerdict::Culled}));
    ASSERT_NE(log.at(0), nullptr);
    EXPECT_EQ(log.at(0)->missed, (std::vector<uint32_t>{1, 4}));
    EXPECT_EQ(log.at(0)->drawn_hidden, (std::vector<uint32_t>{2}));
    EXPECT_EQ(log.at(1), nullptr) << "not recorded";
    ASSERT_NE(log.at(2), nullptr);
    EXPECT_TRUE(log.at(2)->missed.empty());
    EXPECT_EQ(log.at(2)->drawn_hidden, (std::vector<uint32_t>{0}));
    EXPECT_EQ(log.at(3), nullptr);
    EXPECT_FALSE(log.overflowed());
}

TEST(VerdictLog, AFramePastTheBudgetEndsTheLogAndSaysSo) {
    // Room for the bookkeeping of two frames and a few objects, not three frames.
    VerdictLog log(2 * sizeof(FrameVerdicts) + 4 * sizeof(uint32_t));
    const std::vector<uint8_t> two_wrong =
        verdicts({ObjectVerdict::Missed, ObjectVerdict::DrawnHidden, ObjectVerdict::DrawnVisible});
    log.record(0, two_wrong);
    log.record(1, two_wrong);
    EXPECT_FALSE(log.overflowed());
    log.record(2, two_wrong);
    EXPECT_TRUE(log.overflowed());
    EXPECT_EQ(log.at(2), nullptr);
    // A small frame after it is not kept either: the log ends, without holes.
    log.record(3, verdicts({ObjectVerdict::DrawnVisible}));
    EXPECT_EQ(log.at(3), nullptr);
    EXPECT_NE(log.at(1), nullptr);
    EXPECT_LE(log.bytes(), 2 * sizeof(FrameVerdicts) + 4 * sizeof(uint32_t));
}

}  // namespace
}  // namespace occsim
