// The decision log of the culling contract (occsim/culling/contract/decision_log.h): the reason
// kinds' names and what they say about drawing, and the log itself.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "occsim/culling/contract/decision_log.h"

namespace occsim {
namespace {

TEST(DecisionKinds, EachKindHasItsOwnNameAndSaysWhetherItDraws) {
    std::set<std::string> names;
    for (uint32_t k = 0; k < kDecisionKinds; ++k) {
        const auto kind = static_cast<DecisionKind>(k);
        const std::string name(decisionKindName(kind));
        EXPECT_FALSE(name.empty()) << k;
        EXPECT_TRUE(names.insert(name).second) << "two kinds are called " << name;
        const int draws = decisionKindDraws(kind);
        EXPECT_TRUE(draws == -1 || draws == 0 || draws == 1) << name;
        // The names say it: a kind that draws starts with "drawn", one that culls not.
        if (draws == 1) {
            EXPECT_EQ(name.rfind("drawn", 0), 0u) << name;
        }
        if (draws == 0) {
            EXPECT_NE(name.rfind("drawn", 0), 0u) << name;
        }
    }
    EXPECT_EQ(decisionKindName(DecisionKind::CulledOnQuery), "culled on query");
    EXPECT_EQ(decisionKindDraws(DecisionKind::DrawnConditional), -1);
    EXPECT_EQ(decisionKindDraws(DecisionKind::NoReasonGiven), -1);
    EXPECT_EQ(decisionKindName(static_cast<DecisionKind>(kDecisionKinds)), "unknown reason");
}

TEST(DecisionKinds, AnAnswerSaysItsFrameItsSamplesAndWhetherTheCullerWaited) {
    QueryAnswer occluded;
    occluded.visible = false;
    occluded.samples = 0;
    occluded.waited = true;
    const Decision culled = answeredDecision(176, occluded);
    EXPECT_EQ(culled.kind, DecisionKind::CulledOnQuery);
    EXPECT_EQ(culled.query_frame, 176u);
    EXPECT_EQ(culled.flags & kDecisionWaited, kDecisionWaited);

    QueryAnswer visible;
    visible.samples = uint64_t{1} << 40;  // saturates rather than wraps
    const Decision drawn = answeredDecision(3, visible);
    EXPECT_EQ(drawn.kind, DecisionKind::DrawnOnQuery);
    EXPECT_EQ(drawn.samples, UINT32_MAX);
    EXPECT_EQ(drawn.flags & kDecisionWaited, 0);
}

TEST(DecisionLog, RecordsInOrderOnlyWhenThereIsALogAndKeepsItsRoomWhenCleared) {
    recordDecision(nullptr, QueryTag::object(1), decisionOf(DecisionKind::DrawnNoTest));  // no-op
    DecisionLog log;
    log.reserve(8);
    recordDecision(&log, QueryTag::node(4), decisionOf(DecisionKind::FrustumCulled));
    recordDecision(&log, QueryTag::object(2), decisionOf(DecisionKind::DrawnNoTest));
    ASSERT_EQ(log.records().size(), 2u);
    EXPECT_EQ(log.records()[0].subject, QueryTag::node(4));
    EXPECT_EQ(log.records()[1].decision.kind, DecisionKind::DrawnNoTest);
    const DecisionRecord* storage = log.records().data();
    log.clear();
    EXPECT_TRUE(log.records().empty());
    recordDecision(&log, QueryTag::object(0), decisionOf(DecisionKind::DrawnNoTest));
    EXPECT_EQ(log.records().data(), storage) << "a cleared log reuses its storage";
}

}  // namespace
}  // namespace occsim
