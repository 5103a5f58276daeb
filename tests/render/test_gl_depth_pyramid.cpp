// The GPU depth pyramid (render/gl_depth_pyramid.h) on a real headless context: its levels hold
// the farthest depth of what they cover on a viewport of odd size, in both depth conventions; a
// box behind an occluder is hidden and others show, as boxes and as spheres, next to the origin
// and 10^6 m from it; a box the near plane reaches is visible without a test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>

#include "occsim/culling/geometry/hzb_rules.h"
#include "render/gl_depth_pyramid.h"
#include "render/gl_query_device.h"
#include "render/gl_renderer.h"
#include "render/headless_context.h"
#include "render_test_scene.h"

namespace occsim {
namespace {

// A unit cube [-0.5, 0.5]^3.
MeshData cubeMesh() {
    MeshData m;
    for (int i = 0; i < 8; ++i) {
        m.positions.push_back(
            glm::vec3((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f));
        m.normals.push_back(glm::normalize(m.positions.back()));
    }
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return m;
}

class GlDepthPyramidTest : public ::testing::TestWithParam<DepthConvention> {
  protected:
    static constexpr uint32_t kW = 67, kH = 45;  // odd: the base (64 x 32) covers up to 3x3
    void SetUp() override {
        context_ = createHeadlessContext({Backend::Egl, {}}, kW, kH);
        renderer_ = std::make_unique<GlRenderer>(kW, kH, GetParam());
        const MeshData cube = cubeMesh();
        renderer_->uploadMeshes(std::span<const MeshData>(&cube, 1));
        renderer_->setObjectMeshes(std::vector<uint32_t>{0, 0, 0});
        device_ = std::make_unique<GlQueryDevice>(*renderer_, LatencyMode{});
        // Object 0: a wall at z = -5; object 1: a cube hidden behind it; object 2: a cube beside.
        boxes_ = {{{-3, -3, -5.1f}, {3, 3, -4.9f}},
                  {{-0.5f, -0.5f, -20.5f}, {0.5f, 0.5f, -19.5f}},
                  {{11.5f, -0.5f, -20.5f}, {12.5f, 0.5f, -19.5f}}};
    }
    // Places the scene at `origin` (world) with the eye there; boxes stay in the culling frame.
    void setView(glm::dvec3 origin) {
        ViewSetup view;
        view.eye = origin;
        view.box_origin = origin;
        view.view_rotation = glm::mat4(1.0f);
        view.projection =
            perspectiveFor(GetParam(), glm::radians(90.0f), float(kW) / kH, 0.1f, 1000.0f);
        model_view_.clear();
        for (const Aabb& b : boxes_) {
            const glm::dvec3 c = 0.5 * (glm::dvec3(b.min) + glm::dvec3(b.max));
            const glm::dvec3 world = origin + c;
            model_view_.push_back(glm::mat4(glm::translate(glm::dmat4(1.0), world - view.eye) *
                                            glm::scale(glm::dmat4(1.0), glm::dvec3(extent(b)))));
        }
        renderer_->setView(view, model_view_);
    }
    std::vector<uint8_t> test(std::span<const Aabb> boxes, PyramidBound shape) {
        std::vector<uint8_t> visible(boxes.size(), 9);
        device_->depthPyramid()->testBounds(boxes, shape, visible);
        return visible;
    }
    std::unique_ptr<HeadlessContext> context_;
    std::unique_ptr<GlRenderer> renderer_;
    std::unique_ptr<GlQueryDevice> device_;
    std::vector<Aabb> boxes_;
    std::vector<glm::mat4> model_view_;
};

TEST_P(GlDepthPyramidTest, TheDeviceOffersTheCapability) {
    EXPECT_NE(device_->depthPyramid(), nullptr);
    EXPECT_TRUE(device_->features() & kDepthPyramid);
}

// Every texel of level 0 is the farthest stored depth of the pixels it covers (up to 3x3 on this
// odd viewport), and every later texel the farthest of the 2x2 below it.
TEST_P(GlDepthPyramidTest, EachTexelHoldsTheFarthestDepthOfWhatItCovers) {
    const bool reverse = GetParam() == DepthConvention::ReverseFloat;
    setView(glm::dvec3(0.0));
    renderer_->beginFrame();
    device_->drawObject(0);
    device_->drawObject(2);
    auto* pyramid = static_cast<GlDepthPyramid*>(device_->depthPyramid());
    pyramid->build();
    // The stored depths, as the depth texture reads them.
    std::vector<uint32_t> ranks;
    renderer_->readDepthRanks(ranks);
    std::vector<float> depth(ranks.size());
    for (size_t i = 0; i < ranks.size(); ++i) {
        if (reverse) {
            std::memcpy(&depth[i], &ranks[i], sizeof(float));
        } else {
            depth[i] = static_cast<float>(double(0xFFFFFFu - ranks[i]) / double(0xFFFFFFu));
        }
    }
    std::vector<float> below, level;
    uint32_t below_w = kW, below_h = kH;
    below = depth;
    for (uint32_t l = 0; l < pyramid->levelCount(); ++l) {
        uint32_t w = 0, h = 0;
        pyramid->readLevel(l, level, &w, &h);
        ASSERT_EQ(w, hzb::levelSize(64, l));
        ASSERT_EQ(h, hzb::levelSize(32, l));
        for (uint32_t y = 0; y < h; ++y) {
            for (uint32_t x = 0; x < w; ++x) {
                float farthest = reverse ? INFINITY : -INFINITY;
                for (uint32_t fy = hzb::firstCovered(y, below_h, h);
                     fy <= hzb::lastCovered(y, below_h, h); ++fy) {
                    for (uint32_t fx = hzb::firstCovered(x, below_w, w);
                         fx <= hzb::lastCovered(x, below_w, w); ++fx) {
                        const float d = below[size_t{fy} * below_w + fx];
                        farthest = reverse ? std::min(farthest, d) : std::max(farthest, d);
                    }
                }
                ASSERT_NEAR(level[size_t{y} * w + x], farthest, reverse ? 0.0 : 1e-7)
                    << "level " << l << " texel " << x << "," << y;
            }
        }
        below = level;
        below_w = w;
        below_h = h;
    }
}

// The wall hides the cube behind it and not the one beside; the wall's own box shows (ties pass);
// the same 10^6 m from the origin, where the boxes must be projected relative to the eye.
TEST_P(GlDepthPyramidTest, ABoxBehindTheWallIsHiddenAndTheOthersShow) {
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, -3e5, 1e6)}) {
        setView(origin);
        renderer_->beginFrame();
        device_->drawObject(0);
        device_->drawObject(2);
        device_->depthPyramid()->build();
        for (const PyramidBound shape : {PyramidBound::Box, PyramidBound::Sphere}) {
            EXPECT_EQ(test(boxes_, shape), (std::vector<uint8_t>{1, 0, 1}))
                << "origin " << origin.x << " sphere " << (shape == PyramidBound::Sphere);
        }
    }
    EXPECT_EQ(device_->counters().pyramid_builds, 2u);
    EXPECT_EQ(device_->counters().pyramid_bounds, 12u);
}

// Rule 5: a box from behind the eye to behind the wall, whose corners' projections mean nothing,
// is visible without a test; so is one that only reaches the near plane.
TEST_P(GlDepthPyramidTest, ABoxTheNearPlaneReachesIsVisibleWithoutATest) {
    setView(glm::dvec3(0.0));
    renderer_->beginFrame();
    device_->drawObject(0);
    device_->depthPyramid()->build();
    const std::vector<Aabb> boxes = {{{-0.2f, -0.2f, -30.0f}, {0.2f, 0.2f, 1.0f}},
                                     {{-0.01f, -0.01f, -30.0f}, {0.01f, 0.01f, -0.05f}}};
    for (const PyramidBound shape : {PyramidBound::Box, PyramidBound::Sphere}) {
        EXPECT_EQ(test(boxes, shape), (std::vector<uint8_t>{1, 1}));
    }
}

INSTANTIATE_TEST_SUITE_P(Conventions, GlDepthPyramidTest, bothDepthConventions(),
                         depthConventionName);

}  // namespace
}  // namespace occsim
