// Two-phase hierarchical-Z culling without OpenGL (culling/cullers/hzb_culler.h): the culler's two
// phases, the near-plane rule, and a property test against the exact depth raster over random
// scenes, views and viewport sizes. The rules themselves: test_software_depth_pyramid.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <string>

#include "culling/cullers/hzb_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/geometry/hzb_rules.h"
#include "occsim/culling/testing/depth_raster_device.h"
#include "occsim/culling/testing/scripted_query_device.h"
#include "occsim/culling/testing/software_depth_pyramid.h"

namespace occsim {
namespace {

using hzb::TexelRect;

// --- The culler ----------------------------------------------------------------------------------

// A device whose pyramid hides every bound it is asked about: what the culler draws anyway is
// what it decided without a test.
class HidingPyramidDevice final : public RenderDevice, private DepthPyramid {
  public:
    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override { drawn.push_back(object); }
    QueryId issueQuery(std::span<const Aabb>, std::span<const QueryTag>) override { return 0; }
    bool isQueryReady(QueryId) override { return true; }
    QueryAnswer takeAnswer(QueryId) override { return {}; }
    DepthPyramid* depthPyramid() override { return this; }
    void build() override { ++builds; }
    void testBounds(std::span<const Aabb> boxes, PyramidBound,
                    std::span<uint8_t> visible) override {
        tested.insert(tested.end(), boxes.begin(), boxes.end());
        std::fill(visible.begin(), visible.end(), uint8_t{0});
    }
    std::vector<uint32_t> drawn;
    std::vector<Aabb> tested;
    int builds = 0;
};

// Rule 5: an object whose box the near plane reaches is drawn without a test, even when the
// pyramid would hide it (a clipped bound's projection means nothing).
TEST(HzbCuller, AnObjectTheNearPlaneReachesIsDrawnWithoutATest) {
    for (const bool node_units : {false, true}) {
        // Object 0 around the eye, object 1 just in front of it within the near radius, object 2
        // far ahead.
        const std::vector<Aabb> boxes = {
            {glm::vec3(-1, -1, -1), glm::vec3(1, 1, 1)},
            {glm::vec3(-0.1f, -0.1f, -0.15f), glm::vec3(0.1f, 0.1f, -0.101f)},
            {glm::vec3(-1, -1, -30), glm::vec3(1, 1, -28)}};
        const BspTree tree = testing::buildTree(boxes, 1);
        HzbOptions options;
        options.node_units = node_units;
        HzbCuller culler(options);
        culler.reset(tree);
        HidingPyramidDevice device;
        const CullView view = testing::makeView({0, 0, 0}, {0, 0, -10}, 60.0f, 0.1f, 100.0f);
        for (uint64_t f = 0; f < 3; ++f) {
            device.drawn.clear();
            culler.cullAndRender(tree, testing::makeFrame(view, f, f / 30.0), device);
            std::vector<uint32_t> drawn = device.drawn;
            std::sort(drawn.begin(), drawn.end());
            EXPECT_EQ(drawn, (std::vector<uint32_t>{0, 1}))
                << "frame " << f << " nodes " << node_units;
        }
    }
}

// Phase 2 rewrites every object's visibility: an object drawn in phase 1 because it was visible
// last frame, and now hidden, drops out; nothing visible is ever missed, even across a camera
// cut.
TEST(HzbCuller, ObjectsHiddenNowDropOutOfTheNextFramesFirstPhase) {
    std::vector<Aabb> boxes;
    for (int i = 0; i < 8; ++i) {  // a wall across x = -12..12 at z = -1..0
        const float x = -12.0f + 3.0f * static_cast<float>(i);
        boxes.push_back({glm::vec3(x, 0, -1), glm::vec3(x + 3.0f, 10, 0)});
    }
    const uint32_t wall = static_cast<uint32_t>(boxes.size());
    for (int i = 0; i < 6; ++i) {  // a field behind it
        const float x = -6.0f + 2.0f * static_cast<float>(i);
        boxes.push_back({glm::vec3(x, 1, -20), glm::vec3(x + 1.0f, 2, -19)});
    }
    const BspTree tree = testing::buildTree(boxes, 2);
    HzbCuller culler;
    culler.reset(tree);
    DepthRasterDevice device(64, 48);
    // Frames 0-1 look at the field from behind it (the wall out of view); frames 2.. from behind
    // the wall (a camera cut).
    const auto camera = [](uint64_t f) {
        return f < 2 ? std::pair{glm::vec3(0, 2, -40), glm::vec3(0, 2, -19)}
                     : std::pair{glm::vec3(0, 2, 10), glm::vec3(0, 2, -19)};
    };
    for (uint64_t f = 0; f < 6; ++f) {
        const auto [eye, target] = camera(f);
        const glm::mat4 vp = glm::perspective(glm::radians(60.0f), 4.0f / 3.0f, 0.1f, 1000.0f) *
                             glm::lookAt(eye, target, glm::vec3(0, 1, 0));
        CullView view = testing::makeView(eye, target);
        device.beginFrame(vp, eye, boxes);
        culler.cullAndRender(tree, testing::makeFrame(view, f, f / 30.0), device);
        const std::vector<uint8_t> truth = device.groundTruth();
        std::vector<uint8_t> drawn(boxes.size(), 0);
        for (uint32_t o : device.drawnObjects()) drawn[o] = 1;
        for (uint32_t o = 0; o < boxes.size(); ++o) {
            EXPECT_FALSE(truth[o] && !drawn[o]) << "frame " << f << " missed object " << o;
        }
        uint32_t field_drawn = 0;
        for (uint32_t o = wall; o < boxes.size(); ++o) field_drawn += drawn[o];
        if (f < 2) {
            EXPECT_EQ(field_drawn, boxes.size() - wall) << "frame " << f;
        }
        // Frame 2 draws the field in phase 1 (visible last frame) and finds it hidden; frame 3
        // draws only the wall in phase 1, and the field stays hidden.
        if (f >= 3) {
            EXPECT_EQ(field_drawn, 0u) << "frame " << f;
        }
    }
}

// The property: over random scenes, views and viewport sizes, with the camera moving and
// cutting, no object the exact depth raster sees is culled, in every combination of options;
// and the pyramid does cull (it is not frustum culling in disguise).
TEST(HzbCuller, NeverCullsAnObjectTheExactDepthBufferSees) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::uniform_int_distribution<uint32_t> size(1, 160);
    uint64_t hidden_drawn = 0, hidden_in_frustum = 0;
    for (int scene = 0; scene < 24; ++scene) {
        std::vector<Aabb> boxes = testing::randomBoxes(150, 100 + scene, 40.0f);
        for (int i = 0; i < 12; ++i) {  // large thin occluders
            const glm::vec3 c(30.0f * u(rng), 5.0f * u(rng), 30.0f * u(rng));
            const bool thin_x = u(rng) > 0.0f;
            const glm::vec3 half = thin_x ? glm::vec3(0.01f, 6, 8) : glm::vec3(8, 6, 0.01f);
            boxes.push_back({c - half, c + half});
        }
        const BspTree tree = testing::buildTree(boxes, 1 + scene % 6);
        HzbOptions options;
        options.sphere_bounds = scene % 2 == 1;
        options.node_units = scene % 4 >= 2;
        HzbCuller culler(options);
        culler.reset(tree);
        const uint32_t w = size(rng), h = size(rng);
        DepthRasterDevice device(w, h);
        glm::vec3 eye(50.0f * u(rng), 3.0f * u(rng), 50.0f * u(rng));
        glm::vec3 target(10.0f * u(rng), 0.0f, 10.0f * u(rng));
        for (uint64_t f = 0; f < 12; ++f) {
            if (f % 5 == 4) {  // a cut
                eye = glm::vec3(50.0f * u(rng), 3.0f * u(rng), 50.0f * u(rng));
                target = glm::vec3(10.0f * u(rng), 0.0f, 10.0f * u(rng));
            } else {
                eye += glm::vec3(u(rng), 0.1f * u(rng), u(rng));
            }
            const float aspect = float(w) / float(h);
            const float near = f % 3 == 0 ? 1e-3f : 0.1f;
            const glm::mat4 vp = glm::perspective(glm::radians(60.0f), aspect, near, 1e4f) *
                                 glm::lookAt(eye, target, glm::vec3(0, 1, 0));
            CullView view = testing::makeView(eye, target, 60.0f, near, 1e4f, aspect);
            view.view_projection = vp;
            view.viewport_width = w;
            view.viewport_height = h;
            device.beginFrame(vp, eye, boxes);
            culler.cullAndRender(tree, testing::makeFrame(view, f, f / 30.0), device);
            const std::vector<uint8_t> truth = device.groundTruth();
            std::vector<uint8_t> drawn(boxes.size(), 0);
            for (uint32_t o : device.drawnObjects()) drawn[o] = 1;
            for (uint32_t o = 0; o < boxes.size(); ++o) {
                ASSERT_FALSE(truth[o] && !drawn[o]) << "scene " << scene << " frame " << f << " "
                                                    << w << "x" << h << " missed object " << o;
                // Settled frames: two after the start or a cut (the first draws what was visible in
                // the old view, the second what the first found).
                if (f < 2 || f % 5 == 4 || f % 5 == 0) continue;
                const bool in_frustum = classify(view.frustum, boxes[o]) != FrustumTest::Outside;
                hidden_in_frustum += in_frustum && !truth[o];
                hidden_drawn += drawn[o] && !truth[o];
            }
        }
    }
    ASSERT_GT(hidden_in_frustum, 1000u);
    EXPECT_LT(hidden_drawn, hidden_in_frustum / 2)
        << "once settled, the pyramid culls most hidden objects";
}

// --- The capability ------------------------------------------------------------------------------

TEST(HzbCuller, ADeviceWithoutADepthPyramidRefusesItWithOneLine) {
    const CullerRow* hzb = findCuller("hzb");
    ASSERT_NE(hzb, nullptr);
    EXPECT_EQ(hzb->device_needs, uint32_t{kDepthPyramid | kGpuDrivenDraws});
    DepthRasterDevice without(8, 8, 0, /*with_pyramid=*/false);
    try {
        requireDeviceFeatures(*hzb, without.features());
        ADD_FAILURE() << "refused nothing";
    } catch (const RegistryError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "culler 'hzb' needs a depth pyramid (compute shaders), which this device "
                  "does not offer");
    }
    ScriptedQueryDevice scripted;  // neither capability
    try {
        requireDeviceFeatures(*hzb, scripted.features());
        ADD_FAILURE() << "refused nothing";
    } catch (const RegistryError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "culler 'hzb' needs a depth pyramid (compute shaders) and GPU-driven draws "
                  "(multi-draw indirect and storage buffers), which this device does not offer");
    }
    DepthRasterDevice with(8, 8);
    EXPECT_NO_THROW(requireDeviceFeatures(*hzb, with.features()));
}

}  // namespace
}  // namespace occsim
