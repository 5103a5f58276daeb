// The scripted query device (occsim/culling/testing/scripted_query_device.h) and the query contract
// it keeps: answers decided by the device, ids checked in every build, conditional rendering.
#include <gtest/gtest.h>

#include <vector>

#include "culling_fixtures.h"
#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/testing/depth_raster_device.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

using testing::TwoObjects;

TEST(QueryAnswer, SaysVisibleTheSamplesAndWhetherTheCallerWaited) {
    TwoObjects w;
    ScriptedQueryDevice device(2);  // ready after 2 later commands
    device.setVisibility({1, 0}, w.boxes);
    const QueryId seen = device.issueQuery(w.both);
    const QueryId hidden = device.issueQuery(w.boxes[1]);
    device.drawObject(0);  // 2 commands after `seen`, 1 after `hidden`
    EXPECT_TRUE(device.isQueryReady(seen));
    const QueryAnswer a = device.takeAnswer(seen);
    EXPECT_TRUE(a.visible);
    EXPECT_EQ(a.samples, 1u);
    EXPECT_FALSE(a.waited) << "it was ready";
    const QueryAnswer b = device.takeAnswer(hidden);  // one command short of ready
    EXPECT_FALSE(b.visible);
    EXPECT_EQ(b.samples, 0u);
    EXPECT_TRUE(b.waited);
    EXPECT_EQ(device.counters().results_waited, 1u);
}

// Taking an answer twice, or asking about an id never issued, is a bug in the caller: the test
// devices abort with a message naming the device, the call and the id, in every build.
TEST(QueryAnswerDeathTest, TakingAnAnswerTwiceAbortsWithAMessage) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    TwoObjects w;
    ScriptedQueryDevice device(0);
    device.setVisibility({1, 1}, w.boxes);
    const QueryId id = device.issueQuery(w.boxes[0]);
    device.takeAnswer(id);
    EXPECT_DEATH(
        device.takeAnswer(id),
        "ScriptedQueryDevice::takeAnswer: query id 0 is not in flight \\(already taken\\)");
    EXPECT_DEATH(device.isQueryReady(id), "ScriptedQueryDevice::isQueryReady: query id 0 is not");
}

TEST(QueryAnswerDeathTest, AnIdNeverIssuedAbortsWithAMessage) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    ScriptedQueryDevice scripted(0);
    EXPECT_DEATH(scripted.takeAnswer(7),
                 "ScriptedQueryDevice::takeAnswer: query id 7 was never issued");
    DepthRasterDevice raster(4, 4);
    EXPECT_DEATH(raster.isQueryReady(3), "DepthRasterDevice::isQueryReady: query id 3 was never");
}

TEST(ScriptedQueryDevice, NoWaitDrawsUntilTheAnswerIsReadyThenFollowsIt) {
    const std::vector<Aabb> boxes = {{glm::vec3(0), glm::vec3(1)}, {glm::vec3(5), glm::vec3(6)}};
    ScriptedQueryDevice device(2);
    device.setVisibility({0, 1}, boxes);
    ConditionalRendering& c = *device.conditionalRendering();
    const QueryId hidden = device.issueQuery(boxes[0]);
    // Ready once more than 2 commands (the query's own included) followed its issue.
    c.drawIf(hidden, 0, ConditionWait::NoWait);  // 1 command: not ready, drawn
    c.drawIf(hidden, 0, ConditionWait::NoWait);  // 2 commands: still not ready, drawn
    c.drawIf(hidden, 0, ConditionWait::Wait);    // waits: skipped
    c.drawIf(hidden, 0, ConditionWait::NoWait);  // 4 commands: ready, skipped
    const QueryId shown = device.issueQuery(boxes[1]);
    c.drawIf(shown, 1, ConditionWait::Wait);
    c.release(hidden);
    c.release(shown);
    EXPECT_EQ(device.drawnObjects(), (std::vector<uint32_t>{0, 0, 1}));
    EXPECT_EQ(device.skippedObjects(), (std::vector<uint32_t>{0, 0}));
    EXPECT_EQ(device.counters().objects_drawn, 5u) << "submitted draws";
    EXPECT_EQ(device.counters().conditional_draws, 5u);
    EXPECT_EQ(device.counters().results_fetched, 0u);
    EXPECT_EQ(device.pendingQueries(), 0u);
}

TEST(ConditionalRenderingDeathTest, UsingOrReleasingAnIdNotInFlightAbortsWithAMessage) {
    ScriptedQueryDevice device;
    device.setVisibility({1}, {Aabb{glm::vec3(0), glm::vec3(1)}});
    ConditionalRendering& c = *device.conditionalRendering();
    EXPECT_DEATH(c.drawIf(5, 0, ConditionWait::Wait),
                 "ScriptedQueryDevice::drawIf: query id 5 was never issued");
    const QueryId q = device.issueQuery(Aabb{glm::vec3(0), glm::vec3(1)});
    c.release(q);
    EXPECT_DEATH(c.release(q), "ScriptedQueryDevice::release: query id 0 is not in flight");
}

}  // namespace
}  // namespace occsim
