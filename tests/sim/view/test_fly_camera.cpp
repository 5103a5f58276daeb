// The flying camera (sim/view/fly_camera.h): it takes over a pose, flies along its direction at its
// speed, turns with drags, stops short of vertical, and the wheel scales its speed.
#include <gtest/gtest.h>

#include "sim/view/fly_camera.h"

namespace occsim {
namespace {

TEST(FlyCamera, TakesOverAPoseAndFliesAlongItsDirectionAtItsSpeed) {
    FlyCamera camera(2.0);
    camera.setPose({{1, 2, 3}, {1, 2, -7}});  // looking down -z
    const CameraPose pose = camera.pose();
    EXPECT_NEAR(glm::length(glm::normalize(pose.target - pose.position) - glm::dvec3(0, 0, -1)),
                0.0, 1e-12);

    FlyInput forward;
    forward.forward = 1;
    camera.fly(forward, 1.5);
    EXPECT_NEAR(glm::length(camera.position() - glm::dvec3(1, 2, 0)), 0.0, 1e-12);

    FlyInput diagonal;  // no faster than straight on
    diagonal.forward = 1;
    diagonal.right = 1;
    diagonal.fast = true;
    const glm::dvec3 before = camera.position();
    camera.fly(diagonal, 0.5);
    EXPECT_NEAR(glm::length(camera.position() - before), 2.0 * FlyCamera::kFastFactor * 0.5, 1e-12);
    EXPECT_GT(camera.position().x, before.x);  // right of -z is +x
}

TEST(FlyCamera, DragsTurnRightAndDownAndPitchStopsShortOfVertical) {
    FlyCamera camera;
    camera.setPose({{0, 0, 0}, {0, 0, -1}});
    camera.look(90.0 / FlyCamera::kLookDegPerPixel, 0.0);  // a quarter turn right: +x
    EXPECT_NEAR(glm::length(camera.forward() - glm::dvec3(1, 0, 0)), 0.0, 1e-9);
    camera.look(0.0, 1e6);  // far down
    EXPECT_NEAR(glm::degrees(std::asin(camera.forward().y)), -FlyCamera::kMaxPitchDeg, 1e-9);
}

TEST(FlyCamera, TheWheelScalesTheSpeed) {
    FlyCamera camera(4.0);
    camera.changeSpeed(2);
    EXPECT_DOUBLE_EQ(camera.speed(), 4.0 * FlyCamera::kSpeedStep * FlyCamera::kSpeedStep);
    camera.changeSpeed(-2);
    EXPECT_DOUBLE_EQ(camera.speed(), 4.0);
}

}  // namespace
}  // namespace occsim
