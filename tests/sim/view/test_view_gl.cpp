// What the viewer asks of the renderer and the simulation, headless (no window; on every backend
// the build has): the live
// camera, held worlds and algorithm switches on a SharedWorld, a resizable framebuffer, CPU images
// shown in a default framebuffer, and the composed picture with the node boxes.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <stdexcept>

#include "culling/cullers/statistical_culler.h"
#include "headless_backends.h"
#include "occsim/culling/registry/registry.h"
#include "render/gl_api.h"
#include "render/gl_image_presenter.h"
#include "render/gl_renderer.h"
#include "render/headless_context.h"
#include "sim/run/culler_setup.h"
#include "sim/run/ground_truth.h"
#include "sim/run/simulation.h"
#include "sim/scenario/scenario.h"
#include "sim/view/node_boxes.h"
#include "sim/view/validation_overlay.h"
#include "sim/view/view_picture.h"
#include "sim/world/camera_path.h"

namespace occsim {
namespace {

const std::filesystem::path kSmall =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json";

class ViewGl : public ::testing::TestWithParam<Backend> {
  protected:
    void SetUp() override {
        scenario_ = parseScenarioFile(kSmall);
        context_ = createHeadlessContext({GetParam(), {}}, scenario_.width, scenario_.height);
        scene_ = std::make_unique<Scene>(buildScene(scenario_));
        renderer_ = std::make_unique<GlRenderer>(scenario_.width, scenario_.height);
        uploadScene(*scene_, *renderer_);
    }
    std::unique_ptr<Simulation> simulation(const std::string& algorithm, bool error = false) {
        const CullerRow& a = *findCuller(algorithm);
        SimulationOptions options;
        options.measure_error = error;
        return std::make_unique<Simulation>(*scene_, scenario_, a, makeCuller(a, scenario_.culler),
                                            scenario_.culler, *renderer_, options);
    }
    std::vector<uint32_t> ids() {
        std::vector<uint32_t> out;
        renderer_->readObjectIds(out);
        return out;
    }

    Scenario scenario_;
    std::unique_ptr<HeadlessContext> context_;
    std::unique_ptr<Scene> scene_;
    std::unique_ptr<GlRenderer> renderer_;
};

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

size_t countColour(const RasterCanvas& canvas, Rgb colour) {
    size_t n = 0;
    for (uint32_t y = 0; y < canvas.height(); ++y) {
        for (uint32_t x = 0; x < canvas.width(); ++x) n += canvas.at(int(x), int(y)) == colour;
    }
    return n;
}

TEST_P(ViewGl, NodeBoxesShowInTheColoursOfWhatTheCullerDidOnlyForATracedFrame) {
    auto sim = simulation("chc");
    ViewLayers layers;
    layers.boxes = true;
    layers.hud = false;
    std::vector<uint8_t> rgba;
    const Rgb visible = nodeClassColour(NodeClass::DrawnAfterQuery);

    sim->renderFrame();  // not traced: nothing to draw boxes from
    renderer_->readColor(rgba);
    const RasterCanvas plain = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  *sim, scenario_.camera, layers, {});
    EXPECT_EQ(
        countColour(plain, visible),
        countColour(canvasFromBottomUp(rgba, renderer_->width(), renderer_->height()), visible));

    LiveControls controls;
    controls.trace_every_frame = true;
    sim->world().setLiveControls(controls);
    for (int f = 0; f < 3; ++f) sim->renderFrame();  // CHC settles into querying
    renderer_->readColor(rgba);
    const RasterCanvas boxed = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  *sim, scenario_.camera, layers, {});
    EXPECT_GT(countColour(boxed, visible), 100u);
    EXPECT_GT(countColour(boxed, nodeClassColour(NodeClass::OcclusionCulled)), 20u);
}

// A culler that draws nothing: everything ground truth sees is missed.
class DrawsNothing final : public Culler {
  public:
    void reset(const BspTree&) override {}
    void cullAndRender(const BspTree&, const CullFrame&, RenderDevice&) override {}
};

// The validation overlay shows each object's verdict against ground truth, from the same
// comparison as the run's counts: VFC over-draws (yellow boxes) and misses nothing; a culler that
// draws nothing misses what ground truth sees (its pixels tinted red) and over-draws nothing.
TEST_P(ViewGl, TheValidationOverlayShowsMissedDrawnHiddenAndCulledObjects) {
    ViewLayers layers;
    layers.hud = false;
    std::vector<uint8_t> rgba;
    auto verdicts = [](const Simulation& sim, ObjectVerdict v) {
        const auto& all = sim.objectVerdicts();
        return static_cast<int64_t>(std::count(all.begin(), all.end(), static_cast<uint8_t>(v)));
    };
    auto vfc = simulation("vfc", true);
    const FrameStats stats = vfc->renderFrame();
    ASSERT_EQ(vfc->objectVerdicts().size(), scene_->objectCount());
    EXPECT_EQ(verdicts(*vfc, ObjectVerdict::Missed), stats.missed_objects);
    EXPECT_EQ(verdicts(*vfc, ObjectVerdict::DrawnHidden), stats.overdrawn_objects);
    EXPECT_EQ(verdicts(*vfc, ObjectVerdict::DrawnVisible),
              stats.visible_objects - stats.missed_objects);
    EXPECT_GT(stats.overdrawn_objects, 0);
    renderer_->readColor(rgba);
    const RasterCanvas plain = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  *vfc, scenario_.camera, layers, {});
    layers.validation = true;
    const RasterCanvas shown = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  *vfc, scenario_.camera, layers, {});
    EXPECT_GT(countColour(shown, kDrawnHiddenColour), countColour(plain, kDrawnHiddenColour) + 100);
    EXPECT_EQ(countColour(shown, kMissedColour), countColour(plain, kMissedColour));

    const CullerRow& vfc_traits = *findCuller("vfc");
    SimulationOptions options;
    options.measure_error = true;
    Simulation nothing(*scene_, scenario_, vfc_traits, std::make_unique<DrawsNothing>(),
                       scenario_.culler, *renderer_, options);
    const FrameStats none = nothing.renderFrame();
    EXPECT_EQ(verdicts(nothing, ObjectVerdict::Missed), none.visible_objects);
    EXPECT_EQ(verdicts(nothing, ObjectVerdict::DrawnHidden), 0);
    renderer_->readColor(rgba);  // the empty culled frame, before ground truth draws over it
    GroundTruth truth(*renderer_);
    const std::vector<uint32_t> truth_ids = truth.of(nothing.world()).ids;
    layers.truth_ids = truth_ids;
    const RasterCanvas holes = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  nothing, scenario_.camera, layers, {});
    size_t reddish = 0;  // the missed objects' pixels, tinted red over the empty frame
    for (uint32_t y = 0; y < holes.height(); ++y) {
        for (uint32_t x = 0; x < holes.width(); ++x) {
            const Rgb c = holes.at(static_cast<int>(x), static_cast<int>(y));
            reddish += c.r > 120 && c.g < 60 && c.b < 60;
        }
    }
    size_t seen = 0;
    for (uint32_t id : truth_ids) seen += id != 0;
    EXPECT_GE(reddish, seen / 2) << "the missed objects' pixels, " << seen << " of them";
    EXPECT_GT(countColour(holes, kMissedColour), 100u) << "their boxes";
    EXPECT_GT(countColour(holes, kCulledColour), 100u) << "the hidden ones' boxes, grey";
}

INSTANTIATE_TEST_SUITE_P(Backends, ViewGl, ::testing::ValuesIn(testing::testedBackends()),
                         testing::backendTestName);

}  // namespace
}  // namespace occsim
