// The receivers from a camera's depth buffer (sim/run/visible_receivers.h): each covered pixel's
// point lands in the mask where the scene point it shows is, in both depth conventions and
// 10^6 m from the origin; the background adds nothing.
#include <gtest/gtest.h>

#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "depth_conventions.h"
#include "render/gl_renderer.h"
#include "sim/run/visible_receivers.h"

namespace occsim {
namespace {

class VisibleReceivers : public ::testing::TestWithParam<DepthConvention> {};

// A camera 10 m above a floor at y = 0 looking straight down; one pixel of a 4 x 4 buffer covers
// the floor, the rest is background. The mask keeps exactly the caster above that pixel's point.
TEST_P(VisibleReceivers, APixelsPointLandsWhereItsSurfaceIs) {
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, 0.0, -1e6)}) {
        ViewSetup camera;
        camera.eye = origin + glm::dvec3(0, 10, 0);
        camera.view_rotation =
            glm::mat4(glm::lookAt(glm::dvec3(0.0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, -1)));
        camera.projection = perspectiveFor(GetParam(), glm::radians(90.0f), 1.0f, 0.5f, 100.0f);
        // The rank a fragment 10 m away stores, by the renderer's own rule.
        const bool reverse = GetParam() == DepthConvention::ReverseFloat;
        const glm::mat4& p = camera.projection;
        const double z_clip = -double(p[2][2]) * 10.0 + double(p[3][2]);
        uint32_t rank = 0;
        if (reverse) {
            const float stored = static_cast<float>(z_clip / 10.0);
            std::memcpy(&rank, &stored, sizeof rank);
        } else {
            rank = 0xFFFFFFu - static_cast<uint32_t>(
                                   std::floor((0.5 * (z_clip / 10.0) + 0.5) * double(0xFFFFFFu)));
        }
        std::vector<uint32_t> depth(16, 0);
        depth[1 * 4 + 3] = rank;  // row 1, column 3: ndc (0.75, -0.25)
        // The floor point there: x = 7.5 m right, y 0, and up on screen is -z: z = +2.5 m.
        const glm::dvec3 seen = origin + glm::dvec3(7.5, 0.0, 2.5);

        const auto corners = viewFrustumCorners(camera.eye, origin, 90, 1, 0.5, 100);
        const LightBox box = fitDirectionalLight(
            {0, -1, 0}, corners,
            WorldBox{origin + glm::dvec3(-20, -1, -20), origin + glm::dvec3(20, 5, 20)});
        ReceiverMask mask;
        mask.reset(box, 128);
        addVisibleReceivers(depth, 4, 4, camera, GetParam(), 0.05, mask);
        const glm::dvec3 culling_origin = origin;
        auto caster = [&](glm::dvec3 at) {
            const glm::vec3 c(at - culling_origin);
            return Aabb{c - glm::vec3(0.1f), c + glm::vec3(0.1f)};
        };
        EXPECT_TRUE(mask.mayShadow(caster(seen + glm::dvec3(0, 3, 0)), culling_origin));
        EXPECT_FALSE(mask.mayShadow(caster(seen + glm::dvec3(1.0, 3, 0)), culling_origin));
        EXPECT_FALSE(mask.mayShadow(caster(seen + glm::dvec3(0, 3, 1.0)), culling_origin));
        EXPECT_FALSE(mask.mayShadow(caster(seen + glm::dvec3(0, -1, 0)), culling_origin))
            << "under the point";
        EXPECT_LE(mask.coveredTexels(), 9u);
    }
}

INSTANTIATE_TEST_SUITE_P(Depth, VisibleReceivers, bothDepthConventions(), depthConventionName);

}  // namespace
}  // namespace occsim
