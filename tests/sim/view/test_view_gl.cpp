// What the viewer asks of the renderer and the simulation, headless (no window; on every backend
// the build has): the live camera, held worlds and algorithm switches on a SharedWorld, a
// resizable framebuffer. Cullers made as runs make them: tests/sim/run/test_culler_setup.cpp; CPU
// images shown in a default framebuffer: tests/render/test_gl_image_presenter.cpp; the node boxes
// and the validation overlay: test_node_boxes.cpp and test_validation_overlay.cpp.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "culling/cullers/statistical_culler.h"
#include "render/gl_api.h"
#include "render/gl_image_presenter.h"
#include "view_gl_fixture.h"

namespace occsim {
namespace {

TEST_P(ViewGl, ALiveCameraOnThePathsPoseRendersThePathsFrame) {
    auto on_path = simulation("vfc");
    auto live = simulation("vfc");
    for (uint32_t f = 0; f < 6; ++f) {
        on_path->renderFrame();
        const std::vector<uint32_t> expected = ids();
        LiveControls controls;
        controls.camera = sampleCameraPath(scenario_.camera, f * scenario_.dt_s);
        live->world().setLiveControls(controls);
        live->renderFrame();
        EXPECT_EQ(ids(), expected) << "frame " << f;
    }
}

TEST_P(ViewGl, AHeldWorldKeepsItsPosesWhileFramesGoOn) {
    auto sim = simulation("statistical");
    for (int f = 0; f < 3; ++f) sim->renderFrame();
    const std::vector<Aabb> boxes = sim->state().boxes;
    LiveControls controls;
    controls.hold_world = true;
    sim->world().setLiveControls(controls);
    for (int f = 0; f < 3; ++f) sim->renderFrame();
    EXPECT_EQ(sim->world().nextFrame(), 6u);
    for (size_t o = 0; o < boxes.size(); ++o) {
        ASSERT_EQ(sim->state().boxes[o].min, boxes[o].min) << o;
        ASSERT_EQ(sim->state().boxes[o].max, boxes[o].max) << o;
    }
    sim->world().setLiveControls({});
    sim->renderFrame();
    size_t moved = 0;
    for (size_t o = 0; o < boxes.size(); ++o) moved += sim->state().boxes[o].min != boxes[o].min;
    EXPECT_GT(moved, 0u);
}

// The viewer keeps its world and puts a new configuration on it.
TEST_P(ViewGl, ASwitchedAlgorithmContinuesTheWorldWhereItWas) {
    SharedWorld world(*scene_, scenario_);
    GroundTruth truth(*renderer_);
    auto onWorld = [&](const std::string& algorithm, bool error) {
        const CullerRow& a = *findCuller(algorithm);
        SimulationOptions options;
        options.measure_error = error;
        return std::make_unique<Simulation>(world, truth, a, makeCuller(a, scenario_.culler),
                                            scenario_.culler, *renderer_, options);
    };
    auto first = onWorld("chc", false);
    auto reference = simulation("vfc");  // a world of its own
    for (int f = 0; f < 5; ++f) {
        world.advance();
        first->renderFrame();
        reference->renderFrame();
    }
    first.reset();
    auto second = onWorld("statistical", true);
    EXPECT_EQ(world.nextFrame(), 5u);
    for (int f = 0; f < 3; ++f) {
        world.advance();
        reference->renderFrame();
        const FrameStats stats = second->renderFrame();
        EXPECT_EQ(stats.frame, reference->world().frame());
        EXPECT_EQ(stats.error_pixels, 0);  // a conservative culler on the same world
        for (uint32_t o = 0; o < scene_->objectCount(); ++o) {
            ASSERT_EQ(second->state().boxes[o].min, reference->state().boxes[o].min) << o;
        }
    }
    // A shared world's frame is rendered once per configuration: a second render of it is a
    // caller's mistake, not a new frame.
    EXPECT_THROW(second->renderFrame(), std::logic_error);
}

TEST_P(ViewGl, TheFramebufferFollowsANewSize) {
    renderer_->resize(96, 64);
    auto sim = simulation("vfc");
    LiveControls controls;
    controls.width = 96;
    controls.height = 64;
    sim->world().setLiveControls(controls);
    sim->renderFrame();
    const std::vector<uint32_t> small = ids();
    ASSERT_EQ(small.size(), 96u * 64u);
    EXPECT_GT(std::count_if(small.begin(), small.end(), [](uint32_t id) { return id != 0; }),
              96 * 64 / 4);
}

INSTANTIATE_TEST_SUITE_P(Backends, ViewGl, ::testing::ValuesIn(testing::testedBackends()),
                         testing::backendTestName);

}  // namespace
}  // namespace occsim
