// GPU-driven draws on OpenGL (render/gl_gpu_driven_draws.h) on a real headless context, in both
// depth conventions: both phases' commands written and drawn on the GPU with nothing read back in
// the frame, each slot's answer kept for the next frame, both tests (pyramid and box raster)
// hiding what the wall hides and nothing else, next to the origin and 10^6 m from it, on an odd
// viewport, with the eye inside a box; phase 2 in batches; and an indirect draw writes the pixels a
// direct draw does.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <string>

#include "render/gl_gpu_driven_draws.h"
#include "render/gl_query_device.h"
#include "render/gl_renderer.h"
#include "render/headless_context.h"
#include "render_test_scene.h"

namespace occsim {
namespace {

const char* testName(GpuTest test) { return test == GpuTest::Pyramid ? "pyramid" : "box raster"; }

class GlGpuDrivenDrawsTest : public ::testing::TestWithParam<DepthConvention> {
  protected:
    static constexpr uint32_t kW = 67, kH = 45;  // odd on both axes
    void SetUp() override {
        context_ = createHeadlessContext({Backend::Egl, {}}, kW, kH);
        renderer_ = std::make_unique<GlRenderer>(kW, kH, GetParam());
        const MeshData cube = cubeMesh();
        renderer_->uploadMeshes(std::span<const MeshData>(&cube, 1));
        // Object 0: a wall at z = -5; 1: a cube hidden behind it; 2: a cube beside it; 3: a cube
        // behind the wall of which a sliver shows past the wall's edge (about a pixel wide).
        boxes_ = {{{-3, -3, -5.1f}, {3, 3, -4.9f}},
                  {{-0.5f, -0.5f, -20.5f}, {0.5f, 0.5f, -19.5f}},
                  {{15.5f, -0.5f, -20.5f}, {16.5f, 0.5f, -19.5f}},
                  {{3.9f, -0.5f, -8.5f}, {4.9f, 0.5f, -7.5f}}};
        renderer_->setObjectMeshes(std::vector<uint32_t>(boxes_.size(), 0));
        device_ = std::make_unique<GlQueryDevice>(*renderer_, LatencyMode{});
        slots_.resize(boxes_.size());
        for (uint32_t i = 0; i < boxes_.size(); ++i) slots_[i] = i;
        forced_.assign(boxes_.size(), 0);
    }
    // The scene at `origin` (world) with the eye `eye_offset` from it, looking down -z.
    void setView(glm::dvec3 origin, glm::dvec3 eye_offset = glm::dvec3(0.0)) {
        ViewSetup view;
        view.eye = origin + eye_offset;
        view.box_origin = origin;
        view.view_rotation = glm::mat4(1.0f);
        view.projection =
            perspectiveFor(GetParam(), glm::radians(90.0f), float(kW) / kH, 0.1f, 1000.0f);
        view.near_radius = 0.2f;
        model_view_.clear();
        for (const Aabb& b : boxes_) {
            const glm::dvec3 c = 0.5 * (glm::dvec3(b.min) + glm::dvec3(b.max));
            model_view_.push_back(glm::mat4(glm::translate(glm::dmat4(1.0), origin + c - view.eye) *
                                            glm::scale(glm::dmat4(1.0), glm::dvec3(extent(b)))));
        }
        renderer_->setView(view, model_view_);
    }
    struct Frame {
        std::vector<uint8_t> drawn, first_phase, passed;
        uint64_t read_backs_in_frame = 0;
    };
    // One frame through the GPU-driven draws, every object its own unit; phase 2 in the batches
    // `batch_ends` says (none: one); `forgotten` slots forgotten first.
    Frame runFrame(GpuTest test, uint32_t slot_count = 0, std::span<const uint32_t> batch_ends = {},
                   std::span<const uint32_t> forgotten = {}) {
        GpuUnits units;
        units.batch_ends = batch_ends;
        units.forgotten_slots = forgotten;
        units.bounds = boxes_;
        units.slots = slots_;
        units.forced = forced_;
        units.objects = slots_;
        units.object_units = slots_;
        units.slot_count = slot_count != 0 ? slot_count : static_cast<uint32_t>(boxes_.size());
        device_->resetCounters();
        device_->beginDrawnSet(static_cast<uint32_t>(boxes_.size()));
        renderer_->beginFrame();
        GpuDrivenDraws* gpu = device_->gpuDrivenDraws();
        gpu->drawFirstPhase(units);
        gpu->drawSecondPhase(test, PyramidBound::Box);
        renderer_->finish();
        Frame f;
        f.read_backs_in_frame = device_->counters().read_backs;
        device_->resolveGpuDrivenDraws();
        for (uint32_t o = 0; o < boxes_.size(); ++o) f.drawn.push_back(device_->drew(o) ? 1 : 0);
        f.first_phase.assign(boxes_.size(), 0);
        f.passed.assign(boxes_.size(), 0);
        gpu->readResults(f.first_phase, f.passed);
        return f;
    }

    std::unique_ptr<HeadlessContext> context_;
    std::unique_ptr<GlRenderer> renderer_;
    std::unique_ptr<GlQueryDevice> device_;
    std::vector<Aabb> boxes_;
    std::vector<uint32_t> slots_;
    std::vector<uint8_t> forced_;
    std::vector<glm::mat4> model_view_;
};

TEST_P(GlGpuDrivenDrawsTest, TheDeviceOffersBothTests) {
    ASSERT_NE(device_->gpuDrivenDraws(), nullptr);
    EXPECT_EQ(device_->features() & (kGpuDrivenDraws | kBoxRaster), kGpuDrivenDraws | kBoxRaster);
}

// Frame 0 draws everything in phase 2 (nothing was visible); frame 1 draws it all in phase 1 and
// finds the hidden cube hidden; from frame 2 on it is not drawn. Nothing read back in a frame.
TEST_P(GlGpuDrivenDrawsTest, TheWallHidesWhatItHidesAndEachSlotRemembers) {
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, -3e5, 1e6)}) {
        for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
            SCOPED_TRACE(testName(test));
            device_->gpuDrivenDraws()->resetVisibility();
            setView(origin);
            Frame f = runFrame(test);
            EXPECT_EQ(f.drawn, (std::vector<uint8_t>{1, 1, 1, 1}));
            EXPECT_EQ(f.first_phase, (std::vector<uint8_t>{0, 0, 0, 0}));
            EXPECT_EQ(f.passed, (std::vector<uint8_t>{1, 1, 1, 1}));
            f = runFrame(test);
            EXPECT_EQ(f.drawn, (std::vector<uint8_t>{1, 1, 1, 1}));
            EXPECT_EQ(f.first_phase, (std::vector<uint8_t>{1, 1, 1, 1}));
            EXPECT_EQ(f.passed, (std::vector<uint8_t>{1, 0, 1, 1})) << "the sliver shows";
            for (int again = 0; again < 2; ++again) {
                f = runFrame(test);
                EXPECT_EQ(f.drawn, (std::vector<uint8_t>{1, 0, 1, 1}));
                EXPECT_EQ(f.first_phase, (std::vector<uint8_t>{1, 0, 1, 1}));
                EXPECT_EQ(f.passed, (std::vector<uint8_t>{1, 0, 1, 1}));
                EXPECT_EQ(f.read_backs_in_frame, 0u);
            }
        }
    }
}

// Each phase is timed on the CPU and between GPU timestamps, for the frame just resolved only.
TEST_P(GlGpuDrivenDrawsTest, EachPhaseIsTimedForTheFrameJustResolved) {
    setView(glm::dvec3(0.0));
    for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
        runFrame(test);
        const GlGpuDrivenDraws::PhaseTimes* t = device_->gpuDrivenPhaseTimes();
        ASSERT_NE(t, nullptr) << testName(test);
        EXPECT_GT(t->cpu_ms[0] + t->cpu_ms[1] + t->cpu_ms[2], 0.0);
        EXPECT_GT(t->gpu_ms[0] + t->gpu_ms[1] + t->gpu_ms[2], 0.0) << "llvmpipe: its threads' time";
        for (int p = 0; p < 3; ++p) EXPECT_GE(t->cpu_ms[p], 0.0) << p;
    }
    // A frame without GPU-driven draws has no phase times.
    renderer_->beginFrame();
    renderer_->drawObject(0);
    renderer_->finish();
    device_->resolveGpuDrivenDraws();
    EXPECT_EQ(device_->gpuDrivenPhaseTimes(), nullptr);
}

// Phase 2 in batches: the wall (the first batch) is drawn before the cubes (the second) are
// tested, so the hidden cube is not drawn on a frame whose phase 1 drew nothing; the pyramid is
// rebuilt for the second batch. Each batch's test and draws count in the test's and phase 2's
// times.
TEST_P(GlGpuDrivenDrawsTest, ABatchIsTestedAgainstWhatTheBatchesBeforeItDrew) {
    const uint32_t ends[] = {1, 4};
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, -3e5, 1e6)}) {
        for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
            SCOPED_TRACE(testName(test));
            setView(origin);
            device_->gpuDrivenDraws()->resetVisibility();
            Frame f = runFrame(test, 0, ends);
            EXPECT_EQ(f.first_phase, (std::vector<uint8_t>{0, 0, 0, 0}));
            EXPECT_EQ(f.drawn, (std::vector<uint8_t>{1, 0, 1, 1})) << "the sliver shows";
            EXPECT_EQ(f.passed, (std::vector<uint8_t>{1, 0, 1, 1}));
            EXPECT_EQ(f.read_backs_in_frame, 0u);
            const GlGpuDrivenDraws::PhaseTimes* t = device_->gpuDrivenPhaseTimes();
            ASSERT_NE(t, nullptr);
            EXPECT_GT(t->gpu_ms[1] + t->gpu_ms[2], 0.0);
            // Next frame, phase 1 draws what passed; the hidden cube stays hidden.
            f = runFrame(test, 0, ends);
            EXPECT_EQ(f.first_phase, (std::vector<uint8_t>{1, 0, 1, 1}));
            EXPECT_EQ(f.drawn, (std::vector<uint8_t>{1, 0, 1, 1}));
            // In one batch, from forgotten visibility, it passes against the empty depth.
            device_->gpuDrivenDraws()->resetVisibility();
            f = runFrame(test);
            EXPECT_EQ(f.drawn, (std::vector<uint8_t>{1, 1, 1, 1}));
        }
    }
}

// A forgotten slot (a unit index reused for another unit) is not visible to phase 1; the others
// keep their answers.
TEST_P(GlGpuDrivenDrawsTest, AForgottenSlotIsNotDrawnInPhaseOne) {
    device_->gpuDrivenDraws()->resetVisibility();
    setView(glm::dvec3(0.0));
    runFrame(GpuTest::BoxRaster);
    runFrame(GpuTest::BoxRaster);
    const uint32_t forget[] = {2};
    Frame f = runFrame(GpuTest::BoxRaster, 0, {}, forget);
    EXPECT_EQ(f.first_phase, (std::vector<uint8_t>{1, 0, 0, 1}));
    EXPECT_EQ(f.drawn, (std::vector<uint8_t>{1, 0, 1, 1})) << "phase 2 finds it visible";
    f = runFrame(GpuTest::BoxRaster);
    EXPECT_EQ(f.first_phase, (std::vector<uint8_t>{1, 0, 1, 1}));
}

// More slots (a tree that grew nodes) keep the answers of the old ones: phase 1 still draws what
// was visible (forgetting would draw nothing there, and everything in phase 2).
TEST_P(GlGpuDrivenDrawsTest, MoreSlotsKeepTheOldSlotsAnswers) {
    device_->gpuDrivenDraws()->resetVisibility();
    setView(glm::dvec3(0.0));
    runFrame(GpuTest::BoxRaster, 4);
    runFrame(GpuTest::BoxRaster, 4);
    const Frame f = runFrame(GpuTest::BoxRaster, 100000);
    EXPECT_EQ(f.first_phase, (std::vector<uint8_t>{1, 0, 1, 1}));
    EXPECT_EQ(f.drawn, (std::vector<uint8_t>{1, 0, 1, 1}));
}

// A forced unit, and one whose box holds the eye (the renderer's near-plane rule), is drawn in
// phase 1 and passes whatever its test says.
TEST_P(GlGpuDrivenDrawsTest, AForcedUnitAndABoxAroundTheEyePassWithoutATest) {
    for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
        SCOPED_TRACE(testName(test));
        device_->gpuDrivenDraws()->resetVisibility();
        forced_ = {0, 1, 0, 0};  // the hidden cube
        setView(glm::dvec3(0.0));
        for (int frame = 0; frame < 3; ++frame) {
            const Frame f = runFrame(test);
            EXPECT_EQ(f.drawn[1], 1) << frame;
            EXPECT_EQ(f.passed[1], 1) << frame;
        }
        // The eye inside the hidden cube, looking down -z (the wall behind it): the box around
        // the eye passes without a test.
        forced_ = {0, 0, 0, 0};
        device_->gpuDrivenDraws()->resetVisibility();
        setView(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -20.0));
        for (int frame = 0; frame < 3; ++frame) {
            const Frame f = runFrame(test);
            EXPECT_EQ(f.drawn[1], 1) << frame;
            EXPECT_EQ(f.passed[1], 1) << frame;
        }
    }
}

// The indirect path draws the same pixels as direct draws: one program, the same per-instance
// inputs (the object's matrix and ID at its base instance).
TEST_P(GlGpuDrivenDrawsTest, IndirectDrawsWriteThePixelsDirectDrawsWrite) {
    setView(glm::dvec3(1e6, -3e5, 1e6), glm::dvec3(0.3, 0.2, 0.0));
    renderer_->beginFrame();
    for (uint32_t o = 0; o < boxes_.size(); ++o) renderer_->drawObject(o);
    std::vector<uint32_t> direct_ids, indirect_ids;
    std::vector<uint8_t> direct_colour, indirect_colour;
    renderer_->readObjectIds(direct_ids);
    renderer_->readColor(direct_colour);
    device_->gpuDrivenDraws()->resetVisibility();
    runFrame(GpuTest::BoxRaster);  // frame 0: everything drawn, in phase 2
    renderer_->readObjectIds(indirect_ids);
    renderer_->readColor(indirect_colour);
    EXPECT_EQ(direct_ids, indirect_ids);
    EXPECT_EQ(direct_colour, indirect_colour);
    EXPECT_GT(std::count(direct_ids.begin(), direct_ids.end(), 4u), 0) << "the sliver is on screen";
}

INSTANTIATE_TEST_SUITE_P(Conventions, GlGpuDrivenDrawsTest, bothDepthConventions(),
                         depthConventionName);

}  // namespace
}  // namespace occsim
