// The depth raster device (occsim/culling/testing/depth_raster_device.h): answers that depend on
// what was drawn before them, and conditional draws evaluated against them.
#include <gtest/gtest.h>

#include <vector>

#include "culling_fixtures.h"
#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/testing/depth_raster_device.h"

namespace occsim {
namespace {

using testing::Camera;
using testing::makeCamera;

TEST(DepthRasterDevice, ANearerDrawnBoxHidesAFartherOne) {
    const Camera cam = makeCamera({0, 1, 10}, {0, 1, 0});
    DepthRasterDevice device(32, 24);
    const std::vector<Aabb> boxes = {{glm::vec3(-5, -5, -1), glm::vec3(5, 5, 0)},
                                     {glm::vec3(-1, 0, -20), glm::vec3(1, 2, -18)}};
    device.beginFrame(cam.view_projection, cam.view.eye, boxes);
    EXPECT_TRUE(device.takeAnswer(device.issueQuery(boxes[1])).visible) << "nothing drawn yet";
    device.drawObject(0);
    EXPECT_FALSE(device.takeAnswer(device.issueQuery(boxes[1])).visible) << "behind the drawn wall";
    EXPECT_TRUE(device.takeAnswer(device.issueQuery(boxes[0])).visible) << "ties pass";
    // A box containing a hidden object and part of the wall passes; ground truth sees the wall.
    Aabb both = boxes[0];
    extend(both, boxes[1]);
    EXPECT_TRUE(device.takeAnswer(device.issueQuery(both)).visible);
    EXPECT_EQ(device.groundTruth(), (std::vector<uint8_t>{1, 0}));
}

TEST(DepthRasterDevice, AConditionalDrawBehindAWallIsSkippedAndWritesNothing) {
    const Camera cam = makeCamera({0, 1, 10}, {0, 1, 0});
    DepthRasterDevice device(32, 24);
    const std::vector<Aabb> boxes = {{glm::vec3(-5, -5, -1), glm::vec3(5, 5, 0)},
                                     {glm::vec3(-1, 0, -20), glm::vec3(1, 2, -18)},
                                     {glm::vec3(-1, 0, -30), glm::vec3(1, 2, -28)}};
    device.beginFrame(cam.view_projection, cam.view.eye, boxes);
    ConditionalRendering& c = *device.conditionalRendering();
    const QueryId before = device.issueQuery(boxes[1]);  // against an empty raster
    device.drawObject(0);
    const QueryId after = device.issueQuery(boxes[2]);  // behind the wall
    c.drawIf(before, 1, ConditionWait::Wait);
    c.drawIf(after, 2, ConditionWait::Wait);
    c.release(before);
    c.release(after);
    EXPECT_EQ(device.drawnObjects(), (std::vector<uint32_t>{0, 1}))
        << "the answer is the raster's when the query was issued";
    EXPECT_EQ(device.skippedObjects(), (std::vector<uint32_t>{2}));
    EXPECT_EQ(device.counters().objects_drawn, 3u);
    EXPECT_EQ(device.counters().conditional_draws, 2u);
}

}  // namespace
}  // namespace occsim
