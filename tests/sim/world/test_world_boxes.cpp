// The world's boxes in the culling frame (sim/world/world_boxes.cpp): relative to the culling
// origin, rounded outward, the origin staying with the camera however far the objects reach.
#include <gtest/gtest.h>

#include "sim/world/world.h"
#include "small_scenario.h"

namespace occsim {
namespace {

using testing::smallScenario;

// Boxes are relative to the scene's culling origin and rounded outward: far from the world origin
// they still contain the object (a float box rounded to nearest could cut a few centimetres off).
TEST(WorldBoxes, AreRelativeToTheCullingOriginAndRoundedOutward) {
    const Aabb unit{{-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}};
    ObjectPose pose;
    pose.position = {1e6 + 0.01, 3.3, -2e6 - 0.07};
    const glm::dvec3 origin(1e6, 0, -2e6);
    const Aabb near = worldBox(unit, pose, origin);
    EXPECT_NEAR(near.min.x, 0.01 - 0.5, 1e-6);
    EXPECT_NEAR(near.max.z, -0.07 + 0.5, 1e-6);
    const Aabb far = worldBox(unit, pose);  // relative to the world origin: 6 cm float steps
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LE(static_cast<double>(far.min[axis]), pose.position[axis] - 0.5) << axis;
        EXPECT_GE(static_cast<double>(far.max[axis]), pose.position[axis] + 0.5) << axis;
    }
    Scenario s = smallScenario();
    auto& teapots = std::get<TeapotFieldSpec>(s.sources[0].spec);
    teapots.region = {glm::vec3(999980, 0, 4950), glm::vec3(1000020, 5, 5000)};
    s.camera.keyframes = {{0.0, {999990.2, 2, 5010}, {1e6, 1, 4975}},
                          {2.0, {1000010.4, 2, 5040}, {1e6, 1, 4975}}};
    const Scene scene = buildScene(s);
    // The centre of the camera's keyframes, in whole metres: precision where the camera is.
    EXPECT_EQ(scene.culling_origin.x, 1000000.0);
    EXPECT_EQ(scene.culling_origin.z, 5025.0);
}

// A region is in double like the camera: 10^12 m out, the field is where the camera is aimed
// (in float, 10^12 rounds to 999,999,995,904: the scene landed 4 km away).
TEST(WorldBoxes, ARegionFarOutIsWhereTheScenarioPutsIt) {
    Scenario s = smallScenario();
    auto& teapots = std::get<TeapotFieldSpec>(s.sources[0].spec);
    teapots.region = {glm::dvec3(1e12, 0, 0), glm::dvec3(1e12 + 100, 5, 100)};
    s.camera.keyframes = {{0.0, {1e12 + 50, 3, 150}, {1e12 + 50, 1, 50}}};
    const Scene scene = buildScene(s);
    ASSERT_FALSE(scene.initial_poses.empty());
    for (const ObjectPose& p : scene.initial_poses) {
        EXPECT_GE(p.position.x, 1e12);
        EXPECT_LE(p.position.x, 1e12 + 100);
    }
}

// A far object does not pull the origin: one teapot 10^9 m away beside a field at the origin.
TEST(WorldBoxes, TheCullingOriginStaysWithTheCameraWhateverTheObjectsReach) {
    Scenario s = smallScenario();
    TeapotFieldSpec far;
    far.count = 1;
    far.region = {glm::vec3(1e9f, 0, 0), glm::vec3(1e9f + 1, 1, 1)};
    SceneSourceSpec& source = s.sources.emplace_back();
    source.type = SourceType::Teapots;
    source.spec.emplace<TeapotFieldSpec>(far);
    s.camera.keyframes = {{0.0, {3.4, 2, 6}, {0, 1, -20}}};
    const Scene scene = buildScene(s);
    EXPECT_EQ(scene.culling_origin, glm::dvec3(3, 2, 6));
}

}  // namespace
}  // namespace occsim
