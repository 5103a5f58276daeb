// The software device's GPU-driven draws (culling/testing/depth_raster_gpu_draws.cpp, the contract
// of occsim/culling/contract/gpu_driven_draws.h): what each phase draws, the visibility each slot
// keeps across frames, forced units, phase 2 in batches, and the two tests against the same depth.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "culling_fixtures.h"
#include "occsim/culling/testing/depth_raster_device.h"

namespace occsim {
namespace {

using testing::Camera;
using testing::makeCamera;

// A wall (object 0) and two objects behind it (1, 2), each its own unit and slot.
struct WallScene {
    std::vector<Aabb> boxes = {{glm::vec3(-5, -5, -1), glm::vec3(5, 5, 0)},
                               {glm::vec3(-1, 0, -20), glm::vec3(1, 2, -18)},
                               {glm::vec3(-1, 0, -30), glm::vec3(1, 2, -28)}};
    std::vector<uint32_t> slots = {0, 1, 2};
    std::vector<uint8_t> forced = {0, 0, 0};
    std::vector<uint32_t> objects = {0, 1, 2};
    std::vector<uint32_t> object_units = {0, 1, 2};

    GpuUnits units() const {
        GpuUnits u;
        u.bounds = boxes;
        u.slots = slots;
        u.forced = forced;
        u.objects = objects;
        u.object_units = object_units;
        u.slot_count = 3;
        return u;
    }
};

struct PhaseResult {
    std::vector<uint32_t> drawn;
    std::vector<uint8_t> first_phase, passed;
};

PhaseResult runFrame(DepthRasterDevice& device, const WallScene& scene, GpuTest test) {
    const Camera cam = makeCamera({0, 1, 10}, {0, 1, 0});
    device.beginFrame(cam.view_projection, cam.view.eye, scene.boxes);
    GpuDrivenDraws* gpu = device.gpuDrivenDraws();
    gpu->drawFirstPhase(scene.units());
    gpu->drawSecondPhase(test, PyramidBound::Box);
    PhaseResult r;
    r.drawn = device.drawnObjects();
    r.first_phase.assign(scene.boxes.size(), 0);
    r.passed.assign(scene.boxes.size(), 0);
    gpu->readResults(r.first_phase, r.passed);
    return r;
}

TEST(DepthRasterGpuDraws, EachSlotKeepsItsUnitsAnswerForTheNextFramesFirstPhase) {
    for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
        WallScene scene;
        DepthRasterDevice device(32, 24);
        // Frame 0: nothing visible yet, so phase 1 draws nothing and phase 2 tests against an
        // empty depth buffer: everything passes and is drawn.
        PhaseResult r = runFrame(device, scene, test);
        EXPECT_EQ(r.drawn, (std::vector<uint32_t>{0, 1, 2}));
        EXPECT_EQ(r.first_phase, (std::vector<uint8_t>{0, 0, 0}));
        EXPECT_EQ(r.passed, (std::vector<uint8_t>{1, 1, 1}));
        // Frame 1: all three in phase 1; the wall now hides the other two.
        r = runFrame(device, scene, test);
        EXPECT_EQ(r.drawn, (std::vector<uint32_t>{0, 1, 2}));
        EXPECT_EQ(r.first_phase, (std::vector<uint8_t>{1, 1, 1}));
        EXPECT_EQ(r.passed, (std::vector<uint8_t>{1, 0, 0}));
        // Frame 2: only the wall in phase 1; the others stay hidden and are not drawn.
        r = runFrame(device, scene, test);
        EXPECT_EQ(r.drawn, (std::vector<uint32_t>{0}));
        EXPECT_EQ(r.first_phase, (std::vector<uint8_t>{1, 0, 0}));
        EXPECT_EQ(r.passed, (std::vector<uint8_t>{1, 0, 0}));
        EXPECT_EQ(device.counters().read_backs, 0u);
        // Forgotten visibility: phase 1 draws nothing again.
        device.gpuDrivenDraws()->resetVisibility();
        r = runFrame(device, scene, test);
        EXPECT_EQ(r.first_phase, (std::vector<uint8_t>{0, 0, 0}));
        EXPECT_EQ(r.drawn, (std::vector<uint32_t>{0, 1, 2}));
    }
}

TEST(DepthRasterGpuDraws, AForcedUnitIsDrawnInPhaseOneAndPassesWhateverTheDepthSays) {
    for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
        WallScene scene;
        scene.forced = {1, 0, 1};  // the wall and the farthest object
        DepthRasterDevice device(32, 24);
        for (int f = 0; f < 3; ++f) {
            const PhaseResult r = runFrame(device, scene, test);
            EXPECT_EQ(r.first_phase[0], 1) << f;
            EXPECT_EQ(r.first_phase[2], 1) << f;
            EXPECT_EQ(r.passed[2], 1) << "behind the wall, but forced; frame " << f;
            EXPECT_EQ(r.passed[1], 0) << "behind the wall; frame " << f;
        }
    }
}

// Phase 2 in batches: the wall (the first batch) is drawn before the objects behind it (the
// second) are tested, so they are hidden on a frame whose phase 1 drew nothing; in one batch they
// pass against the empty depth.
TEST(DepthRasterGpuDraws, ABatchIsTestedAgainstWhatTheBatchesBeforeItDrew) {
    for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
        WallScene scene;
        const std::vector<uint32_t> ends = {1, 3};
        DepthRasterDevice device(32, 24);
        const Camera cam = makeCamera({0, 1, 10}, {0, 1, 0});
        device.beginFrame(cam.view_projection, cam.view.eye, scene.boxes);
        GpuUnits units = scene.units();
        units.batch_ends = ends;
        device.gpuDrivenDraws()->drawFirstPhase(units);
        device.gpuDrivenDraws()->drawSecondPhase(test, PyramidBound::Box);
        EXPECT_EQ(device.drawnObjects(), (std::vector<uint32_t>{0}));
        std::vector<uint8_t> first_phase(3), passed(3);
        device.gpuDrivenDraws()->readResults(first_phase, passed);
        EXPECT_EQ(first_phase, (std::vector<uint8_t>{0, 0, 0}));
        EXPECT_EQ(passed, (std::vector<uint8_t>{1, 0, 0}));
        // The same frame in one batch, from forgotten visibility: all three pass.
        device.gpuDrivenDraws()->resetVisibility();
        const PhaseResult r = runFrame(device, scene, test);
        EXPECT_EQ(r.drawn, (std::vector<uint32_t>{0, 1, 2}));
    }
}

// A forgotten slot is not visible to phase 1; the other slots keep their answers.
TEST(DepthRasterGpuDraws, AForgottenSlotIsNotDrawnInPhaseOne) {
    WallScene scene;
    scene.boxes[2] = {glm::vec3(20, 0, -30), glm::vec3(22, 2, -28)};  // beside the wall: visible
    DepthRasterDevice device(32, 24);
    runFrame(device, scene, GpuTest::BoxRaster);
    runFrame(device, scene, GpuTest::BoxRaster);
    const Camera cam = makeCamera({0, 1, 10}, {0, 1, 0});
    device.beginFrame(cam.view_projection, cam.view.eye, scene.boxes);
    GpuUnits units = scene.units();
    const std::vector<uint32_t> forget = {2};
    units.forgotten_slots = forget;
    device.gpuDrivenDraws()->drawFirstPhase(units);
    EXPECT_EQ(device.drawnObjects(), (std::vector<uint32_t>{0})) << "slot 2 forgotten";
    device.gpuDrivenDraws()->drawSecondPhase(GpuTest::BoxRaster, PyramidBound::Box);
    EXPECT_EQ(device.drawnObjects(), (std::vector<uint32_t>{0, 2}));
}

// Several entries of one unit (a node's objects) are drawn together, in the phase their unit is.
TEST(DepthRasterGpuDraws, EveryEntryOfAUnitIsDrawnInItsUnitsPhase) {
    WallScene scene;
    scene.boxes = {scene.boxes[0], scene.boxes[1]};  // unit 1 holds objects 1 and 2
    scene.boxes[1] = {glm::vec3(-1, 0, -30), glm::vec3(1, 2, -18)};
    scene.slots = {0, 1};
    scene.forced = {0, 0};
    scene.object_units = {0, 1, 1};
    DepthRasterDevice device(32, 24);
    const Camera cam = makeCamera({0, 1, 10}, {0, 1, 0});
    const std::vector<Aabb> object_boxes = {WallScene().boxes[0], WallScene().boxes[1],
                                            WallScene().boxes[2]};
    device.beginFrame(cam.view_projection, cam.view.eye, object_boxes);
    device.gpuDrivenDraws()->drawFirstPhase(scene.units());
    device.gpuDrivenDraws()->drawSecondPhase(GpuTest::BoxRaster, PyramidBound::Box);
    EXPECT_EQ(device.drawnObjects(), (std::vector<uint32_t>{0, 1, 2}));
    device.beginFrame(cam.view_projection, cam.view.eye, object_boxes);
    device.gpuDrivenDraws()->drawFirstPhase(scene.units());
    EXPECT_EQ(device.drawnObjects(), (std::vector<uint32_t>{0, 1, 2}));
    device.gpuDrivenDraws()->drawSecondPhase(GpuTest::BoxRaster, PyramidBound::Box);
    EXPECT_EQ(device.drawnObjects(), (std::vector<uint32_t>{0, 1, 2})) << "none drawn twice";
}

// Against the same depth, a box the raster passes is passed by the pyramid too (a passing cell
// lies under a texel that holds a depth at least as far): box rasterisation is the tighter test.
TEST(DepthRasterGpuDraws, BoxRasterPassesNoUnitThePyramidHides) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    uint32_t pyramid_only = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const std::vector<Aabb> boxes = testing::randomBoxes(60, 500 + trial, 20.0f);
        const Camera cam = makeCamera({30.0f * u(rng), 2.0f, 30.0f}, {0, 0, 0});
        // The first 20 boxes are drawn (phase 1, forced); the rest tested by both.
        std::vector<uint32_t> slots(boxes.size()), objects(boxes.size());
        std::vector<uint8_t> forced(boxes.size(), 0);
        for (uint32_t i = 0; i < boxes.size(); ++i) slots[i] = objects[i] = i;
        for (uint32_t i = 0; i < 20; ++i) forced[i] = 1;
        GpuUnits units;
        units.bounds = boxes;
        units.slots = slots;
        units.forced = forced;
        units.objects = objects;
        units.object_units = slots;
        units.slot_count = static_cast<uint32_t>(boxes.size());
        std::vector<uint8_t> passed[2];
        const uint32_t w = 17 + static_cast<uint32_t>(trial) * 7, h = 13 + trial * 5u;
        for (int k = 0; k < 2; ++k) {
            DepthRasterDevice device(w, h);
            device.beginFrame(cam.view_projection, cam.view.eye, boxes);
            device.gpuDrivenDraws()->drawFirstPhase(units);
            device.gpuDrivenDraws()->drawSecondPhase(k == 0 ? GpuTest::Pyramid : GpuTest::BoxRaster,
                                                     PyramidBound::Box);
            std::vector<uint8_t> first(boxes.size());
            passed[k].assign(boxes.size(), 0);
            device.gpuDrivenDraws()->readResults(first, passed[k]);
        }
        for (uint32_t i = 0; i < boxes.size(); ++i) {
            ASSERT_FALSE(passed[1][i] && !passed[0][i]) << "trial " << trial << " box " << i;
            pyramid_only += passed[0][i] && !passed[1][i];
        }
    }
    EXPECT_GT(pyramid_only, 0u) << "the pyramid, coarser, passes some boxes the raster hides";
}

}  // namespace
}  // namespace occsim
