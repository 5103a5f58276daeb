// A directional light's shadow box (sim/world/light_view.h): every scene point the camera sees
// lies in it, and every scene point between the light and such a point (a caster of its shadow),
// for lights from every side, straight down, grazing the ground, and 10^6 m from the origin; it is
// no larger across the light than the camera's frustum and the scene allow; a camera that sees
// none of the scene gets no box.
#include <gtest/gtest.h>

#include <random>

#include "sim/world/light_view.h"

namespace occsim {
namespace {

// Inside with a relative tolerance for the rounding of dot products far from the origin.
bool inside(const LightBox& box, const glm::dvec3& world) {
    const glm::dvec3 l = toLightSpace(box, world);
    const double scale = std::max({1.0, std::abs(l.x), std::abs(l.y), std::abs(l.z)});
    const double eps = 1e-12 * scale;
    return l.x >= box.min.x - eps && l.x <= box.max.x + eps && l.y >= box.min.y - eps &&
           l.y <= box.max.y + eps && l.z >= box.min.z - eps && l.z <= box.max.z + eps;
}

bool inScene(const WorldBox& scene, const glm::dvec3& p) {
    return glm::all(glm::greaterThanEqual(p, scene.min)) &&
           glm::all(glm::lessThanEqual(p, scene.max));
}

// A point inside the frustum of `corners`: trilinear between the near and far rectangles.
glm::dvec3 frustumPoint(const std::array<glm::dvec3, 8>& c, double u, double v, double w) {
    auto rect = [&](int plane) {
        const glm::dvec3 bottom = glm::mix(c[plane * 4 + 0], c[plane * 4 + 1], u);
        const glm::dvec3 top = glm::mix(c[plane * 4 + 3], c[plane * 4 + 2], u);
        return glm::mix(bottom, top, v);
    };
    return glm::mix(rect(0), rect(1), w);
}

TEST(LightView, HoldsEveryVisibleScenePointAndEveryCasterOfItsShadow) {
    std::mt19937 rng(55);
    std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
    uint64_t visible_points = 0, casters = 0;
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, 20.0, -1e6)}) {
        for (int trial = 0; trial < 200; ++trial) {
            const WorldBox scene{origin + glm::dvec3(-100.0, 0.0, -80.0),
                                 origin + glm::dvec3(120.0, 40.0 + 40.0 * unit(rng), 90.0)};
            glm::dvec3 direction(sym(rng), -unit(rng), sym(rng));
            if (trial % 10 == 0) direction = glm::dvec3(0.0, -1.0, 0.0);   // noon
            if (trial % 10 == 1) direction = glm::dvec3(1.0, -1e-3, 0.2);  // grazing
            const glm::dvec3 eye =
                origin + glm::dvec3(150.0 * sym(rng), 2.0 + 30.0 * unit(rng), 150.0 * sym(rng));
            const glm::dvec3 target = origin + glm::dvec3(50.0 * sym(rng), 0.0, 50.0 * sym(rng));
            const auto corners = viewFrustumCorners(eye, target, 20.0 + 80.0 * unit(rng),
                                                    0.5 + unit(rng), 0.1, 50.0 + 400.0 * unit(rng));
            const LightBox box = fitDirectionalLight(direction, corners, scene);
            for (int k = 0; k < 200; ++k) {
                const glm::dvec3 p = frustumPoint(corners, unit(rng), unit(rng), unit(rng));
                if (!inScene(scene, p)) continue;
                ++visible_points;
                ASSERT_FALSE(box.empty) << "trial " << trial;
                ASSERT_TRUE(inside(box, p)) << "trial " << trial << " visible point";
                // A caster on the ray toward the light, still inside the scene.
                const glm::dvec3 q = p - box.forward * (500.0 * unit(rng));
                if (!inScene(scene, q)) continue;
                ++casters;
                ASSERT_TRUE(inside(box, q)) << "trial " << trial << " caster";
            }
        }
    }
    EXPECT_GT(visible_points, 10000u);
    EXPECT_GT(casters, 1000u);
}

TEST(LightView, IsNoWiderThanTheFrustumAndTheSceneAllow) {
    const WorldBox scene{glm::dvec3(-1000.0, 0.0, -1000.0), glm::dvec3(1000.0, 50.0, 1000.0)};
    // A narrow camera near the middle, the sun straight down: the box across the light is the
    // frustum's footprint, not the whole scene; in depth it reaches up to the scene's top.
    const auto corners = viewFrustumCorners(glm::dvec3(0.0, 2.0, 0.0), glm::dvec3(0.0, 2.0, -10.0),
                                            30.0, 1.0, 0.1, 100.0);
    const LightBox box = fitDirectionalLight(glm::dvec3(0.0, -1.0, 0.0), corners, scene);
    ASSERT_FALSE(box.empty);
    EXPECT_LT(box.max.x - box.min.x, 100.0);
    EXPECT_LT(box.max.y - box.min.y, 120.0);
    EXPECT_NEAR(box.min.z, -50.0, 1e-9) << "the scene's top, nearest the light";
    EXPECT_GT(box.max.z, -2.0) << "down to what the camera sees";
    EXPECT_LE(box.max.z, 0.0 + 1e-9) << "not below the scene's floor";
}

TEST(LightView, ACameraThatSeesNoneOfTheSceneGetsNoBox) {
    const WorldBox scene{glm::dvec3(-10.0, 0.0, -10.0), glm::dvec3(10.0, 5.0, 10.0)};
    const auto away = viewFrustumCorners(glm::dvec3(0.0, 2.0, 500.0), glm::dvec3(0.0, 2.0, 600.0),
                                         60.0, 1.5, 0.1, 50.0);
    EXPECT_TRUE(fitDirectionalLight(glm::dvec3(0.3, -1.0, 0.2), away, scene).empty);
    EXPECT_TRUE(fitDirectionalLight(glm::dvec3(0.3, -1.0, 0.2), away, WorldBox{}).empty)
        << "no scene at all";
}

TEST(LightView, ItsBasisIsOrthonormalForEveryDirection) {
    for (const glm::dvec3 d : {glm::dvec3(0, -1, 0), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0),
                               glm::dvec3(0, -1, 1e-9), glm::dvec3(3, -4, 5)}) {
        const auto corners = viewFrustumCorners(glm::dvec3(0.0), glm::dvec3(0, 0, -1), 60, 1, 1, 2);
        const LightBox box =
            fitDirectionalLight(d, corners, WorldBox{glm::dvec3(-1), glm::dvec3(1)});
        EXPECT_NEAR(glm::length(box.right), 1.0, 1e-12);
        EXPECT_NEAR(glm::length(box.up), 1.0, 1e-12);
        EXPECT_NEAR(glm::dot(box.right, box.forward), 0.0, 1e-12);
        EXPECT_NEAR(glm::dot(box.up, box.forward), 0.0, 1e-12);
        EXPECT_NEAR(glm::dot(box.right, box.up), 0.0, 1e-12);
        EXPECT_NEAR(glm::length(box.forward - glm::normalize(d)), 0.0, 1e-12);
    }
}

// Light-frustum culling: a box with any point inside the light's box is kept, one beside it,
// beyond its far end or rotated out of it by the light's slant is not; the culling frame may lie
// 10^6 m from the origin.
TEST(LightView, ObjectsInTheLightBoxAreThoseWhoseBoxesOverlapIt) {
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, 0.0, -1e6)}) {
        // The sun straight down on a 20 x 20 x 20 m scene, the camera above looking down at it.
        LightBox box = fitDirectionalLight(
            glm::dvec3(0.0, -1.0, 0.0),
            viewFrustumCorners(origin + glm::dvec3(0, 50, 0), origin + glm::dvec3(0, 0, 0), 60, 1,
                               1, 60),
            WorldBox{origin + glm::dvec3(-10, 0, -10), origin + glm::dvec3(10, 20, 10)});
        ASSERT_FALSE(box.empty);
        // In light space the box spans the scene across (|x|, |z| <= 10) and in depth from the
        // scene's top (y = 20) to its floor (y = 0).
        const std::vector<Aabb> boxes = {
            {{-1, 0, -1}, {1, 2, 1}},          // 0: inside
            {{9.5f, 0, 9.5f}, {12, 1, 12}},    // 1: straddles a corner
            {{11, 0, 0}, {12, 1, 1}},          // 2: beside it across the light
            {{0, -5, 0}, {1, -1, 1}},          // 3: below the floor, beyond its far end
            {{0, 20, 0}, {1, 25, 1}},          // 4: touches its near end
            {{-12, 30, -12}, {-11, 31, -11}},  // 5: above and beside
        };
        std::vector<uint32_t> in;
        objectsInLightBox(box, boxes, origin, in);
        EXPECT_EQ(in, (std::vector<uint32_t>{0, 1, 4}));
        box.empty = true;
        objectsInLightBox(box, boxes, origin, in);
        EXPECT_TRUE(in.empty()) << "no box, no shadow pass";
    }
}

// The light a frame renders a shadow pass for: the first directional light that casts shadows.
TEST(LightView, TheShadowLightIsTheFirstDirectionalLightCastingShadows) {
    LightSpec spot, quiet_sun, sun;
    spot.type = LightType::Spot;
    quiet_sun.casts_shadows = false;
    EXPECT_EQ(firstShadowLight({}), -1);
    EXPECT_EQ(firstShadowLight({spot, quiet_sun}), -1);
    EXPECT_EQ(firstShadowLight({spot, quiet_sun, sun, sun}), 2);
}

}  // namespace
}  // namespace occsim
