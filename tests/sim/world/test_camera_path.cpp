// The camera path (sim/world/camera_path.h): through its keyframes, continuous, held at the ends or
// looped.
#include <gtest/gtest.h>

#include "sim/world/camera_path.h"

namespace occsim {
namespace {

TEST(CameraPath, PassesThroughKeyframesAndHoldsAtTheEnds) {
    CameraSpec camera;
    camera.keyframes = {{0.0, {0, 0, 0}, {0, 0, -1}},
                        {1.0, {10, 0, 0}, {10, 0, -1}},
                        {3.0, {10, 0, -20}, {0, 0, -20}}};
    EXPECT_EQ(sampleCameraPath(camera, -1.0).position, glm::dvec3(0, 0, 0));
    EXPECT_EQ(sampleCameraPath(camera, 1.0).position, glm::dvec3(10, 0, 0));
    EXPECT_EQ(sampleCameraPath(camera, 3.0).position, glm::dvec3(10, 0, -20));
    EXPECT_EQ(sampleCameraPath(camera, 99.0).position, glm::dvec3(10, 0, -20));
    const glm::dvec3 mid = sampleCameraPath(camera, 2.0).position;
    EXPECT_GT(mid.x, 5.0);
    EXPECT_LT(mid.z, -5.0);
}

TEST(CameraPath, IsContinuousAcrossKeyframes) {
    CameraSpec camera;
    camera.keyframes = {{0.0, {0, 0, 0}, {0, 0, -1}},
                        {1.0, {10, 0, 0}, {10, 0, -1}},
                        {2.0, {10, 5, -10}, {0, 0, -20}},
                        {4.0, {0, 0, -30}, {0, 0, -40}}};
    for (double t = 0.0; t < 4.0; t += 0.001) {
        const double step = glm::length(sampleCameraPath(camera, t + 0.001).position -
                                        sampleCameraPath(camera, t).position);
        EXPECT_LT(step, 0.05) << "jump at t = " << t;
    }
}

TEST(CameraPath, LoopsWhenAsked) {
    CameraSpec camera;
    camera.loop = true;
    camera.keyframes = {
        {0.0, {0, 0, 0}, {0, 0, -1}}, {1.0, {10, 0, 0}, {10, 0, -1}}, {2.0, {0, 0, 0}, {0, 0, -1}}};
    const glm::dvec3 a = sampleCameraPath(camera, 0.7).position;
    const glm::dvec3 b = sampleCameraPath(camera, 2.7).position;
    EXPECT_NEAR(glm::length(a - b), 0.0, 1e-9);
}

TEST(CameraPath, TheCamerasUpIsYUnlessItLooksStraightUpOrDown) {
    EXPECT_EQ(cameraWorldUp(glm::dvec3(0, 0, -1)), glm::dvec3(0, 1, 0));
    EXPECT_EQ(cameraWorldUp(glm::normalize(glm::dvec3(1, 0.9, 0))), glm::dvec3(0, 1, 0));
    EXPECT_EQ(cameraWorldUp(glm::dvec3(0, -1, 0)), glm::dvec3(0, 0, 1));
    EXPECT_EQ(cameraWorldUp(glm::dvec3(0, 1, 0)), glm::dvec3(0, 0, 1));
}

}  // namespace
}  // namespace occsim
