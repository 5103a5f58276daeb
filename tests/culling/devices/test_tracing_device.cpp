// The tracing device (occsim/culling/devices/tracing_device.h): what a culler did in one frame,
// recorded for pictures.
#include <gtest/gtest.h>

#include <vector>

#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/devices/tracing_device.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

TEST(TracingDevice, RecordsConditionalDrawsAndMarksTheirQueries) {
    const std::vector<Aabb> boxes = {{glm::vec3(0), glm::vec3(1)}, {glm::vec3(5), glm::vec3(6)}};
    ScriptedQueryDevice inner;
    inner.setVisibility({1, 0}, boxes);
    TracingDevice tracer(inner);
    ASSERT_NE(tracer.conditionalRendering(), nullptr);
    tracer.beginTrace(7);
    tracer.drawObject(0);
    const QueryId q = tracer.issueQuery(boxes[1], QueryTag::object(1));
    tracer.conditionalRendering()->drawIf(q, 1, ConditionWait::Wait);
    tracer.conditionalRendering()->release(q);
    tracer.endTrace();
    const FrameTrace& trace = tracer.trace();
    EXPECT_EQ(trace.drawn_objects, (std::vector<uint32_t>{0, 1})) << "as submitted";
    EXPECT_EQ(trace.conditional_objects, (std::vector<uint32_t>{1}));
    ASSERT_EQ(trace.queries.size(), 1u);
    EXPECT_TRUE(trace.queries[0].conditional);
    EXPECT_FALSE(trace.queries[0].fetched) << "never read back";
    EXPECT_EQ(inner.skippedObjects(), (std::vector<uint32_t>{1})) << "the inner device decided";
    EXPECT_EQ(inner.pendingQueries(), 0u) << "released through the tracer";
    inner.offerConditionalRendering(false);
    EXPECT_EQ(tracer.conditionalRendering(), nullptr);
}

}  // namespace
}  // namespace occsim
