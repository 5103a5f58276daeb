// What the viewer asks of the renderer and the simulation, headless (no window; on every backend
// the build has): cullers made as runs make them, the live camera, held worlds and algorithm
// switches on a SharedWorld, a resizable framebuffer, and CPU images shown in a default
// framebuffer. The node boxes and the validation overlay: test_node_boxes.cpp and
// test_validation_overlay.cpp.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "culling/cullers/statistical_culler.h"
#include "render/gl_api.h"
#include "render/gl_image_presenter.h"
#include "view_gl_fixture.h"

namespace occsim {
namespace {

// The viewer makes its cullers through the run layer's one construction path
// (sim/run/culler_setup.h): a culler that weighs costs gets a cost model measured on this
// renderer, the others are left alone, and a cost model the scenario gives is kept.
TEST_P(ViewGl, CullersAreMadeAsRunsMakeThemWithTheCostModelStep) {
    std::vector<RunConfig> configs{
        RunConfig{"vfc", findCuller("vfc"), scenario_.culler},
        RunConfig{"statistical+", findCuller("statistical+"), scenario_.culler}};
    const auto choice = chooseCostModel(configs, *scene_, scenario_, *renderer_, LatencyMode{});
    ASSERT_TRUE(choice);
    EXPECT_EQ(choice->source, CostModelSource::Calibrated);
    EXPECT_FALSE(configs[0].culler.cost_model.known()) << "vfc weighs no costs";
    ASSERT_TRUE(configs[1].culler.cost_model.known());
    const std::unique_ptr<Culler> culler = makeConfiguredCuller(configs[1]);
    const auto* statistical = dynamic_cast<const StatisticalCuller*>(culler.get());
    ASSERT_NE(statistical, nullptr);
    EXPECT_EQ(statistical->costModel(), configs[1].culler.cost_model);

    Scenario given = scenario_;
    given.culler.cost_model = CostModel{0.5, 0.001, 0.0};
    std::vector<RunConfig> kept{
        RunConfig{"statistical+", findCuller("statistical+"), given.culler}};
    EXPECT_EQ(chooseCostModel(kept, *scene_, given, *renderer_, LatencyMode{})->source,
              CostModelSource::Scenario);
    EXPECT_EQ(kept[0].culler.cost_model, (CostModel{0.5, 0.001, 0.0}));
}

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

TEST_P(ViewGl, APresentedImageFillsTheDefaultFramebuffer) {
    // The presenter draws into a window's default framebuffer; an EGL context made current
    // without a surface has none (headless runs render into framebuffer objects). OSMesa's client
    // buffer stands in for a window here, and test_view_window runs the presenter in a real one.
    if (GetParam() == Backend::Egl)
        GTEST_SKIP() << "a surfaceless EGL context has no default framebuffer";
    // Four quadrants of different colours, rows bottom-up.
    const uint32_t w = scenario_.width, h = scenario_.height;
    std::vector<uint8_t> image(size_t{w} * h * 4);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            uint8_t* p = &image[(size_t{y} * w + x) * 4];
            p[0] = x < w / 2 ? 200 : 10;
            p[1] = y < h / 2 ? 180 : 20;
            p[2] = 77;
            p[3] = 255;
        }
    }
    GlImagePresenter presenter;
    presenter.draw(image, w, h, w, h);
    glFinish();
    std::vector<uint8_t> shown(image.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadPixels(0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h), GL_RGBA, GL_UNSIGNED_BYTE,
                 shown.data());
    EXPECT_EQ(shown, image);
}

INSTANTIATE_TEST_SUITE_P(Backends, ViewGl, ::testing::ValuesIn(testing::testedBackends()),
                         testing::backendTestName);

}  // namespace
}  // namespace occsim
