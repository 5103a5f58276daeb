// Scenes assembled from a scenario (sim/world/scene_assembly.cpp): a teapot field deterministic per
// seed and different across seeds, inside its region with sizes in range, and mover fractions
// that pick distinct objects, never two motions for one.
#include <gtest/gtest.h>

#include "gltf_builder.h"
#include "sim/world/world.h"
#include "small_scenario.h"

namespace occsim {
namespace {

using testing::smallScenario;

TEST(Scene, TeapotFieldIsDeterministicPerSeedAndDiffersAcrossSeeds) {
    const Scene a = buildScene(smallScenario(3));
    const Scene b = buildScene(smallScenario(3));
    const Scene c = buildScene(smallScenario(4));
    ASSERT_EQ(a.objectCount(), 200u);
    for (uint32_t o = 0; o < a.objectCount(); ++o) {
        EXPECT_EQ(a.initial_poses[o].position, b.initial_poses[o].position);
        EXPECT_EQ(a.initial_poses[o].linear, b.initial_poses[o].linear);
    }
    EXPECT_NE(a.initial_poses[0].position, c.initial_poses[0].position);
    ASSERT_EQ(a.initial_movers.size(), b.initial_movers.size());
    for (size_t m = 0; m < a.initial_movers.size(); ++m) {
        EXPECT_EQ(a.initial_movers[m].object, b.initial_movers[m].object);
    }
}
TEST(Scene, PlacesTeapotsInsideTheRegionWithSizesInRange) {
    const Scenario s = smallScenario();
    const Scene scene = buildScene(s);
    const auto& spec = std::get<TeapotFieldSpec>(s.sources[0].spec);
    for (const ObjectPose& p : scene.initial_poses) {
        EXPECT_TRUE(contains(Aabb{glm::vec3(spec.region.min), glm::vec3(spec.region.max)},
                             glm::vec3(p.position)));
        const float scale = glm::length(p.linear[1]);  // the y column: height scale
        EXPECT_GE(scale, spec.size_min_m - 1e-5);
        EXPECT_LE(scale, spec.size_max_m + 1e-5);
    }
    EXPECT_EQ(scene.triangle_count, 200u * scene.meshes[0].triangleCount());
}

TEST(Scene, MoverFractionsPickDistinctObjectsAndNeverTwoMotionsForOne) {
    const Scene scene = buildScene(smallScenario());
    EXPECT_EQ(scene.initial_movers.size(), 50u + 20u);  // 25% and 10% of 200
    std::vector<int> seen(scene.objectCount());
    for (const Mover& m : scene.initial_movers) ++seen[m.object];
    for (int count : seen) EXPECT_LE(count, 1) << "an object carries one motion at most";
}

// A scene's lights: the scenario's first, then each placed glTF source's; a source that places
// nothing ("place": false) brings none.
TEST(Scene, ItsLightsAreTheScenariosThenThePlacedGltfFiles) {
    testing_gltf::GltfBuilder b;
    b.node({{"mesh", b.triangleMesh("Tri")}});
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.doc()["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "directional"}}}}}}};
    testing_gltf::TempDir dir;
    GltfSourceSpec lit;
    lit.path = dir.write("sun.gltf", b.text());
    Scenario s = smallScenario();
    LightSpec spot;
    spot.type = LightType::Spot;
    s.lights.push_back(spot);
    s.sources.push_back({SourceType::Gltf, OccluderRole::BySize, lit});
    Scene scene = buildScene(s);
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].type, LightType::Spot);
    EXPECT_EQ(scene.lights[1].type, LightType::Directional);
    EXPECT_EQ(scene.lights[1].direction, glm::dvec3(0, 0, -1)) << "down the node's -z";
    std::get<GltfSourceSpec>(s.sources.back().spec).place = false;
    scene = buildScene(s);
    EXPECT_EQ(scene.lights.size(), 1u);
}

}  // namespace
}  // namespace occsim
