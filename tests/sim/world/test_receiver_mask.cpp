// Receiver-masked caster culling's mask (sim/world/receiver_mask.h): a caster above receiver
// points may shadow them, one beside them, below them or with no receiver in the mask may not,
// a margin widens them; and the property that makes it conservative, sampled: a caster box
// holding any point between a receiver point and the light is always kept, for lights from many
// sides, next to the origin and 10^6 m from it.
#include <gtest/gtest.h>

#include <random>

#include "sim/world/receiver_mask.h"

namespace occsim {
namespace {

// The light's box over a 40 m square scene 20 m high, seen by a camera above it.
LightBox sceneBox(const glm::dvec3& direction, const glm::dvec3& origin) {
    const auto corners = viewFrustumCorners(origin + glm::dvec3(0, 60, 1), origin, 90, 1, 1, 200);
    return fitDirectionalLight(
        direction, corners,
        WorldBox{origin + glm::dvec3(-20, 0, -20), origin + glm::dvec3(20, 20, 20)});
}

Aabb around(glm::vec3 centre, glm::vec3 half) { return {centre - half, centre + half}; }

TEST(ReceiverMask, KeepsACasterAboveAReceiverAndNoneBesideOrBelowIt) {
    const glm::dvec3 origin(0.0);
    ReceiverMask mask;
    mask.reset(sceneBox({0, -1, 0}, origin), 64);
    EXPECT_FALSE(mask.mayShadow(around({0, 5, 0}, {1, 1, 1}), origin)) << "no receiver yet";
    EXPECT_EQ(mask.coveredTexels(), 0u);
    // The top of a 6 x 6 m slab 1 m high, seen at points 0.25 m apart.
    for (double x = -3.0; x <= 3.0; x += 0.25) {
        for (double z = -3.0; z <= 3.0; z += 0.25)
            mask.addReceiver(origin + glm::dvec3(x, 1, z), 0.0);
    }
    EXPECT_GT(mask.coveredTexels(), 0u);
    EXPECT_TRUE(mask.mayShadow(around({0, 5, 0}, {1, 1, 1}), origin)) << "above it";
    EXPECT_TRUE(mask.mayShadow(around({3.5f, 5, 0}, {1, 1, 1}), origin)) << "over its edge";
    EXPECT_FALSE(mask.mayShadow(around({12, 5, 0}, {1, 1, 1}), origin)) << "beside it";
    EXPECT_FALSE(mask.mayShadow(around({0, -5, 0}, {1, 1, 1}), origin)) << "below it";
    EXPECT_TRUE(mask.mayShadow(around({0, 1, 0}, {1, 0.1f, 1}), origin)) << "touching its top";
    EXPECT_FALSE(mask.mayShadow(around({0, 0.5f, 0}, {1, 0.4f, 1}), origin))
        << "under its top, which is all the mask holds";
    // A margin grows each point: a caster just beside the slab's edge is kept with one.
    EXPECT_FALSE(mask.mayShadow(around({3.8f, 5, 0}, {0.5f, 1, 0.5f}), origin));
    mask.addReceiver(origin + glm::dvec3(3, 1, 0), 0.5);
    EXPECT_TRUE(mask.mayShadow(around({3.8f, 5, 0}, {0.5f, 1, 0.5f}), origin));
}

TEST(ReceiverMask, NeverDropsACasterBetweenAReceiverAndTheLight) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto in = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, 0.0, -1e6)}) {
        for (const glm::dvec3 direction :
             {glm::dvec3(0, -1, 0), glm::dvec3(0.4, -1, 0.3), glm::dvec3(1, -0.2, 0.1),
              glm::dvec3(-0.3, -0.5, -1), glm::dvec3(0.05, -1, -0.01)}) {
            const LightBox box = sceneBox(direction, origin);
            ASSERT_FALSE(box.empty);
            for (const uint32_t resolution : {1u, 16u, 128u}) {
                ReceiverMask mask;
                mask.reset(box, resolution);
                std::vector<glm::dvec3> receivers;  // in the culling frame
                for (int i = 0; i < 200; ++i) {
                    receivers.emplace_back(in(-18, 18), in(0, 18), in(-18, 18));
                    mask.addReceiver(receivers.back() + origin, 0.0);
                }
                for (int i = 0; i < 400; ++i) {
                    // A receiver point, a point toward the light from it, a caster box around
                    // that point, all in the culling frame.
                    const glm::dvec3 p = receivers[i % receivers.size()];
                    const glm::dvec3 q = p - in(0.0, 15.0) * box.forward;
                    const glm::vec3 h(in(0.0, 1.0), in(0.0, 1.0), in(0.0, 1.0));
                    const Aabb caster = around(glm::vec3(q), h);
                    ASSERT_TRUE(mask.mayShadow(caster, origin))
                        << "light " << direction.x << "," << direction.y << "," << direction.z
                        << " resolution " << resolution << " sample " << i;
                }
            }
        }
    }
}

}  // namespace
}  // namespace occsim
