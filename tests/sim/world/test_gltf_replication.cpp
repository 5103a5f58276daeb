// A glTF model replicated over a grid or at random: the copies where the scenario puts them,
// deterministic per seed.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "gltf_files.h"

namespace occsim {
namespace {

using nlohmann::json;
using namespace testing_gltf;
using namespace gltf_files;

GltfReplication grid(uint32_t x, uint32_t z, double spacing) {
    GltfReplication r;
    r.mode = GltfReplication::Mode::Grid;
    r.count_x = x;
    r.count_z = z;
    r.spacing_m = spacing;
    return r;
}

GltfReplication random(uint32_t count, bool yaw) {
    GltfReplication r;
    r.mode = GltfReplication::Mode::Random;
    r.count = count;
    r.region = {glm::vec3(-100, 0, -50), glm::vec3(100, 0, 50)};
    r.random_yaw = yaw;
    return r;
}

TEST(GltfReplication, GridMakesCountXTimesCountZCopiesAtTheSpacing) {
    const SourceOutput one = load(kHouse);
    const SourceOutput out = load(kHouse, 1.0, {5, 0, 7}, grid(3, 2, 40.0));
    ASSERT_EQ(out.objects.size(), 6 * one.objects.size());
    EXPECT_EQ(out.meshes.size(), one.meshes.size());  // copies share the meshes
    const size_t n = one.objects.size();
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 base = one.objects[i].position + glm::dvec3(5, 0, 7);
        EXPECT_NEAR(glm::length(out.objects[i].position - base), 0.0, 1e-9);
        EXPECT_NEAR(glm::length(out.objects[n + i].position - (base + glm::dvec3(40, 0, 0))), 0.0,
                    1e-9);
        EXPECT_NEAR(glm::length(out.objects[3 * n + i].position - (base + glm::dvec3(0, 0, 40))),
                    0.0, 1e-9);
        EXPECT_EQ(out.objects[5 * n + i].linear, one.objects[i].linear);
    }
    // Streets between the copies (the house is 18 x 16 m, the spacing 40 m): one loop per copy.
    EXPECT_EQ(out.lanes.size(), 6u);
    const Aabb bounds = floatBox(sourceBounds(out));
    EXPECT_EQ(glm::vec3(out.region.min), bounds.min);
    EXPECT_EQ(glm::vec3(out.region.max), bounds.max);
    expectBoxNear(floatBox(out.region), {2.0f, -1.0f, -6.0f}, {100.0f, 6.3f, 50.0f}, 0.1f);
}

TEST(GltfReplication, GridSpacingZeroIsTheModelSizePlusTenPercent) {
    const SourceOutput one = load(kHouse);
    const glm::vec3 size = extent(floatBox(one.region));
    const SourceOutput out = load(kHouse, 1.0, {}, grid(2, 2, 0.0));
    const size_t n = one.objects.size();
    EXPECT_NEAR(out.objects[n].position.x - out.objects[0].position.x, 1.1 * size.x, 1e-4);
    EXPECT_NEAR(out.objects[2 * n].position.z - out.objects[0].position.z, 1.1 * size.z, 1e-4);
}

TEST(GltfReplication, RandomCopiesAreDeterministicPerSeedInsideTheRegion) {
    const SourceOutput one = load(kTeapot);
    const SourceOutput a = load(kTeapot, 1.0, {}, random(25, true), 7);
    const SourceOutput b = load(kTeapot, 1.0, {}, random(25, true), 7);
    const SourceOutput c = load(kTeapot, 1.0, {}, random(25, true), 8);
    ASSERT_EQ(a.objects.size(), 25u);
    EXPECT_EQ(a.meshes.size(), 1u);
    bool yawed = false;
    for (size_t i = 0; i < a.objects.size(); ++i) {
        EXPECT_EQ(a.objects[i].position, b.objects[i].position);
        EXPECT_EQ(a.objects[i].linear, b.objects[i].linear);
        // The teapot's node sits at the origin, so each copy's origin is its object's position.
        EXPECT_TRUE(contains(floatBox(random(1, true).region), glm::vec3(a.objects[i].position)));
        yawed = yawed || a.objects[i].linear != one.objects[0].linear;
    }
    EXPECT_TRUE(yawed);
    EXPECT_NE(a.objects[0].position, c.objects[0].position);
    const SourceOutput upright = load(kTeapot, 1.0, {}, random(5, false), 7);
    for (const PlacedObject& o : upright.objects) EXPECT_EQ(o.linear, one.objects[0].linear);
    EXPECT_TRUE(a.lanes.empty());
}

}  // namespace
}  // namespace occsim
