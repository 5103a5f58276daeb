// GPU-driven two-phase culling without OpenGL (culling/cullers/gpu_driven_culler.h) over the
// software device's GPU-driven draws (DepthRasterDevice, depth_raster_gpu_draws.cpp): nothing
// read back in the frame, the near-plane rule, the reasons recorded after the frame, and the
// property test against the exact depth raster for both tests (the pyramid and box rasterisation).
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "culling/cullers/gpu_driven_culler.h"
#include "culling/cullers/hzb_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/contract/decision_log.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/depth_raster_device.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

const char* testName(GpuTest test) { return test == GpuTest::Pyramid ? "pyramid" : "box raster"; }

glm::mat4 viewProjection(glm::vec3 eye, glm::vec3 target, float aspect, float near) {
    return glm::perspective(glm::radians(60.0f), aspect, near, 1e4f) *
           glm::lookAt(eye, target, glm::vec3(0, 1, 0));
}

// Per object: drawn this frame by the device.
std::vector<uint8_t> drawnFlags(const DepthRasterDevice& device, size_t objects) {
    std::vector<uint8_t> drawn(objects, 0);
    for (uint32_t o : device.drawnObjects()) drawn[o] = 1;
    return drawn;
}

// A wall across x = -12..12 at z = -1..0 (objects 0..7) and a field behind it (8..13).
std::vector<Aabb> wallAndField() {
    std::vector<Aabb> boxes;
    for (int i = 0; i < 8; ++i) {
        const float x = -12.0f + 3.0f * static_cast<float>(i);
        boxes.push_back({glm::vec3(x, 0, -1), glm::vec3(x + 3.0f, 10, 0)});
    }
    for (int i = 0; i < 6; ++i) {
        const float x = -6.0f + 2.0f * static_cast<float>(i);
        boxes.push_back({glm::vec3(x, 1, -20), glm::vec3(x + 1.0f, 2, -19)});
    }
    return boxes;
}
constexpr uint32_t kWall = 8;

// The scheme as engines ship it: the device decides and draws both phases, and the culler reads
// nothing back during the frame (the read-back `hzb` reads its flags once a frame: the counter
// can tell them apart).
TEST(GpuDrivenCuller, ReadsNothingBackDuringTheFrame) {
    const std::vector<Aabb> boxes = wallAndField();
    const BspTree tree = testing::buildTree(boxes, 2);
    for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
        GpuDrivenOptions options;
        options.test = test;
        GpuDrivenCuller culler(options);
        culler.reset(tree);
        DepthRasterDevice device(64, 48);
        HzbCuller read_back;
        read_back.reset(tree);
        DepthRasterDevice read_back_device(64, 48);
        const glm::vec3 eye(0, 2, 10), target(0, 2, -19);
        const CullView view = testing::makeView(eye, target);
        for (uint64_t f = 0; f < 4; ++f) {
            device.beginFrame(viewProjection(eye, target, 4.0f / 3.0f, 0.1f), eye, boxes);
            device.resetCounters();
            culler.cullAndRender(tree, testing::makeFrame(view, f, f / 30.0), device);
            EXPECT_EQ(device.counters().read_backs, 0u) << testName(test) << " frame " << f;
            EXPECT_GT(device.counters().objects_drawn, 0u);
            culler.afterFrame(device);

            read_back_device.beginFrame(viewProjection(eye, target, 4.0f / 3.0f, 0.1f), eye, boxes);
            read_back_device.resetCounters();
            read_back.cullAndRender(tree, testing::makeFrame(view, f, f / 30.0), read_back_device);
            if (f > 0) {  // frame 0 draws everything and builds no pyramid
                EXPECT_EQ(read_back_device.counters().read_backs, 1u) << "frame " << f;
            }
        }
    }
}

// Phase 2 rewrites every unit's visibility on the device: after a cut the old view's objects are
// drawn once in phase 1, found hidden, and drop out; nothing visible is missed on the way.
TEST(GpuDrivenCuller, ObjectsHiddenNowDropOutOfTheNextFramesFirstPhase) {
    const std::vector<Aabb> boxes = wallAndField();
    const BspTree tree = testing::buildTree(boxes, 2);
    for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
        GpuDrivenOptions options;
        options.test = test;
        GpuDrivenCuller culler(options);
        culler.reset(tree);
        DepthRasterDevice device(64, 48);
        for (uint64_t f = 0; f < 6; ++f) {
            // Frames 0-1 look at the field from behind it; frames 2.. from behind the wall.
            const glm::vec3 eye = f < 2 ? glm::vec3(0, 2, -40) : glm::vec3(0, 2, 10);
            const glm::vec3 target(0, 2, -19);
            device.beginFrame(viewProjection(eye, target, 4.0f / 3.0f, 0.1f), eye, boxes);
            culler.cullAndRender(
                tree, testing::makeFrame(testing::makeView(eye, target), f, f / 30.0), device);
            culler.afterFrame(device);
            const std::vector<uint8_t> truth = device.groundTruth();
            const std::vector<uint8_t> drawn = drawnFlags(device, boxes.size());
            uint32_t field_drawn = 0;
            for (uint32_t o = 0; o < boxes.size(); ++o) {
                EXPECT_FALSE(truth[o] && !drawn[o])
                    << testName(test) << " frame " << f << " missed object " << o;
                if (o >= kWall) field_drawn += drawn[o];
            }
            if (f < 2) {
                EXPECT_EQ(field_drawn, boxes.size() - kWall) << testName(test);
            }
            if (f >= 3) {
                EXPECT_EQ(field_drawn, 0u) << testName(test) << " frame " << f;
            }
        }
    }
}

// Rule 5 of geometry/hzb_rules.h: a unit the near plane reaches is drawn in phase 1 without a
// test, every frame, and its reason says so; the culler hands it to the device as forced.
TEST(GpuDrivenCuller, AUnitTheNearPlaneReachesIsDrawnInPhaseOneWithoutATest) {
    // Object 0 around the eye, object 1 just in front of it within the near radius, object 2 far
    // ahead.
    const std::vector<Aabb> boxes = {
        {glm::vec3(-1, -1, -1), glm::vec3(1, 1, 1)},
        {glm::vec3(-0.1f, -0.1f, -0.15f), glm::vec3(0.1f, 0.1f, -0.101f)},
        {glm::vec3(-1, -1, -30), glm::vec3(1, 1, -28)}};
    const BspTree tree = testing::buildTree(boxes, 1);
    for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
        GpuDrivenOptions options;
        options.test = test;
        GpuDrivenCuller culler(options);
        culler.reset(tree);
        DepthRasterDevice device(32, 32);
        const glm::vec3 eye(0, 0, 0), target(0, 0, -10);
        for (uint64_t f = 0; f < 3; ++f) {
            device.beginFrame(viewProjection(eye, target, 1.0f, 0.1f), eye, boxes);
            DecisionLog log;
            CullFrame frame = testing::makeFrame(
                testing::makeView(eye, target, 60.0f, 0.1f, 1e4f, 1.0f), f, f / 30.0);
            frame.decisions = &log;
            culler.cullAndRender(tree, frame, device);
            culler.afterFrame(device);
            const std::vector<uint8_t> drawn = drawnFlags(device, boxes.size());
            ASSERT_EQ(culler.lastUnits(), 3u);
            uint32_t near_records = 0;
            for (const DecisionRecord& r : log.records()) {
                if (r.subject != QueryTag::object(0) && r.subject != QueryTag::object(1)) continue;
                ++near_records;
                EXPECT_TRUE(drawn[r.subject.index]) << testName(test) << " frame " << f;
                EXPECT_EQ(r.decision.kind, DecisionKind::DrawnNearPlane) << testName(test);
                EXPECT_EQ(r.decision.phase, 1);
            }
            EXPECT_EQ(near_records, 2u) << testName(test) << " frame " << f;
        }
    }
}

// The reasons recorded after the frame name the test that decided: the pyramid's kinds for the
// pyramid, the box raster's for boxes, phase 1 for what was visible last frame.
TEST(GpuDrivenCuller, ItsReasonsNameTheTestAndThePhase) {
    const std::vector<Aabb> boxes = wallAndField();
    const BspTree tree = testing::buildTree(boxes, 2);
    for (const GpuTest test : {GpuTest::Pyramid, GpuTest::BoxRaster}) {
        GpuDrivenOptions options;
        options.test = test;
        GpuDrivenCuller culler(options);
        culler.reset(tree);
        DepthRasterDevice device(64, 48);
        const glm::vec3 eye(0, 2, 10), target(0, 2, -19);
        for (uint64_t f = 0; f < 3; ++f) {
            device.beginFrame(viewProjection(eye, target, 4.0f / 3.0f, 0.1f), eye, boxes);
            DecisionLog log;
            CullFrame frame = testing::makeFrame(testing::makeView(eye, target), f, f / 30.0);
            frame.decisions = &log;
            culler.cullAndRender(tree, frame, device);
            EXPECT_TRUE(log.records().empty() ||
                        std::all_of(log.records().begin(), log.records().end(),
                                    [](const DecisionRecord& r) {
                                        return r.decision.kind == DecisionKind::FrustumCulled;
                                    }))
                << "the device's decisions are recorded only after the frame";
            culler.afterFrame(device);
            const std::vector<uint8_t> drawn = drawnFlags(device, boxes.size());
            const DecisionKind culled = test == GpuTest::Pyramid ? DecisionKind::CulledOnPyramid
                                                                 : DecisionKind::CulledOnBoxRaster;
            const DecisionKind passed = test == GpuTest::Pyramid ? DecisionKind::DrawnOnPyramid
                                                                 : DecisionKind::DrawnOnBoxRaster;
            uint32_t culled_records = 0, phase_one = 0;
            for (const DecisionRecord& r : log.records()) {
                if (r.decision.kind == DecisionKind::FrustumCulled) continue;
                ASSERT_EQ(r.subject.subject, QueryTag::Subject::Object);
                const uint32_t o = r.subject.index;
                if (r.decision.kind == culled) {
                    ++culled_records;
                    EXPECT_FALSE(drawn[o]) << "object " << o << " culled but drawn";
                    EXPECT_EQ(r.decision.phase, 2);
                } else {
                    EXPECT_EQ(r.decision.kind, passed) << "object " << o;
                    EXPECT_TRUE(drawn[o]) << "object " << o << " passed but not drawn";
                    phase_one += r.decision.phase == 1;
                }
            }
            uint32_t wall_in_frustum = 0;
            for (uint32_t o = 0; o < kWall; ++o) {
                wall_in_frustum += classify(frame.view.frustum, boxes[o]) != FrustumTest::Outside;
            }
            ASSERT_GT(wall_in_frustum, 0u);
            if (f >= 2) {  // frame 1 draws the field in phase 1 (seen in frame 0), then culls it
                EXPECT_EQ(culled_records, boxes.size() - kWall) << testName(test);
            }
            if (f >= 2) {
                EXPECT_EQ(phase_one, wall_in_frustum) << testName(test) << ": the wall in phase 1";
            }
        }
    }
}

// The property: over random scenes, views and viewport sizes, with the camera moving and
// cutting, no object the exact depth raster sees is culled, for both tests and every option; the
// tests do cull; rasterising boxes draws no more than the pyramid, and in 4 batches no more than
// in one; and the pyramid decided on the device draws, frame by frame, exactly what the read-back
// `hzb` (HzbCuller) draws.
TEST(GpuDrivenCuller, NeverCullsAnObjectTheExactDepthBufferSees) {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::uniform_int_distribution<uint32_t> size(1, 160);
    uint64_t hidden_in_frustum = 0, hidden_drawn[3] = {0, 0, 0}, drawn_total[3] = {0, 0, 0};
    for (int scene = 0; scene < 16; ++scene) {
        std::vector<Aabb> boxes = testing::randomBoxes(150, 300 + scene, 40.0f);
        for (int i = 0; i < 12; ++i) {  // large thin occluders
            const glm::vec3 c(30.0f * u(rng), 5.0f * u(rng), 30.0f * u(rng));
            const glm::vec3 half = u(rng) > 0.0f ? glm::vec3(0.01f, 6, 8) : glm::vec3(8, 6, 0.01f);
            boxes.push_back({c - half, c + half});
        }
        const BspTree tree = testing::buildTree(boxes, 1 + scene % 6);
        const uint32_t w = size(rng), h = size(rng);
        GpuDrivenCuller* cullers[3];
        GpuDrivenOptions options[3];
        options[0].test = GpuTest::Pyramid;
        options[0].shape = scene % 2 == 1 ? PyramidBound::Sphere : PyramidBound::Box;
        options[1].test = options[2].test = GpuTest::BoxRaster;
        options[0].node_units = options[1].node_units = options[2].node_units = scene % 4 >= 2;
        options[2].batches = 4;
        GpuDrivenCuller pyramid(options[0]), raster(options[1]), batched(options[2]);
        cullers[0] = &pyramid;
        cullers[1] = &raster;
        cullers[2] = &batched;
        DepthRasterDevice devices[3] = {DepthRasterDevice(w, h), DepthRasterDevice(w, h),
                                        DepthRasterDevice(w, h)};
        for (GpuDrivenCuller* c : cullers) c->reset(tree);
        HzbOptions hzb_options;
        hzb_options.sphere_bounds = options[0].shape == PyramidBound::Sphere;
        hzb_options.node_units = options[0].node_units;
        HzbCuller read_back(hzb_options);
        read_back.reset(tree);
        DepthRasterDevice read_back_device(w, h);
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
            const glm::mat4 vp = viewProjection(eye, target, aspect, near);
            CullView view = testing::makeView(eye, target, 60.0f, near, 1e4f, aspect);
            view.view_projection = vp;
            view.viewport_width = w;
            view.viewport_height = h;
            const bool settled = !(f < 2 || f % 5 == 4 || f % 5 == 0);
            read_back_device.beginFrame(vp, eye, boxes);
            read_back.cullAndRender(tree, testing::makeFrame(view, f, f / 30.0), read_back_device);
            const std::vector<uint8_t> read_back_drawn = drawnFlags(read_back_device, boxes.size());
            for (int k = 0; k < 3; ++k) {
                devices[k].beginFrame(vp, eye, boxes);
                cullers[k]->cullAndRender(tree, testing::makeFrame(view, f, f / 30.0), devices[k]);
                cullers[k]->afterFrame(devices[k]);
                const std::vector<uint8_t> truth = devices[k].groundTruth();
                const std::vector<uint8_t> drawn = drawnFlags(devices[k], boxes.size());
                if (k == 0) {
                    ASSERT_EQ(drawn, read_back_drawn) << "scene " << scene << " frame " << f;
                }
                for (uint32_t o = 0; o < boxes.size(); ++o) {
                    ASSERT_FALSE(truth[o] && !drawn[o])
                        << testName(options[k].test) << " batches " << options[k].batches
                        << " scene " << scene << " frame " << f << " " << w << "x" << h
                        << " missed object " << o;
                    if (!settled) continue;
                    const bool in_frustum =
                        classify(view.frustum, boxes[o]) != FrustumTest::Outside;
                    if (k == 0) hidden_in_frustum += in_frustum && !truth[o];
                    hidden_drawn[k] += drawn[o] && !truth[o];
                    drawn_total[k] += drawn[o];
                }
            }
        }
    }
    ASSERT_GT(hidden_in_frustum, 1000u);
    // Spheres and nodes (half the scenes each) cull less than boxes of objects.
    EXPECT_LT(hidden_drawn[0], hidden_in_frustum * 2 / 3) << "the pyramid culls hidden objects";
    EXPECT_LT(hidden_drawn[1], hidden_in_frustum / 3) << "box raster culls most hidden objects";
    EXPECT_LE(drawn_total[1], drawn_total[0]) << "box raster draws no more than the pyramid";
    EXPECT_LT(drawn_total[2], drawn_total[1]) << "in 4 batches, fewer than in one";
    EXPECT_LT(hidden_drawn[2], hidden_drawn[1]);
}

// With node_units, a node index the tree reuses (a merge frees it, a split takes it) stands for
// another node: its slot is forgotten, as the read-back hzb's NodeStateArray forgets its state, so
// the two draw the same objects frame by frame while objects move and the tree adapts.
TEST(GpuDrivenCuller, WithNodeUnitsAReusedNodesSlotIsForgottenAsTheReadBackHzbForgetsIt) {
    std::mt19937 rng(44);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Aabb> boxes = testing::randomBoxes(300, 7, 30.0f);
    for (int i = 0; i < 10; ++i) {  // thin walls, so that something is hidden
        const glm::vec3 c(20.0f * u(rng), 0.0f, 20.0f * u(rng));
        boxes.push_back({c - glm::vec3(6, 0, 0.01f), c + glm::vec3(6, 5, 0.01f)});
    }
    BspTree tree = testing::buildTree(boxes, 2);
    GpuDrivenOptions options;
    options.node_units = true;
    GpuDrivenCuller gpu_driven(options);
    HzbOptions hzb_options;
    hzb_options.node_units = true;
    HzbCuller read_back(hzb_options);
    gpu_driven.reset(tree);
    read_back.reset(tree);
    DepthRasterDevice device(96, 64), read_back_device(96, 64);
    const glm::vec3 eye(0, 2, 45), target(0, 0, 0);
    const glm::mat4 vp = viewProjection(eye, target, 1.5f, 0.1f);
    CullView view = testing::makeView(eye, target, 60.0f, 0.1f, 1e4f, 1.5f);
    view.view_projection = vp;
    view.viewport_width = 96;
    view.viewport_height = 64;
    uint64_t forgotten = 0;
    for (uint64_t f = 0; f < 40; ++f) {
        // A third of the small objects gather into a corner and scatter again: leaves split
        // where they crowd and merge where they left, reusing node indices.
        for (uint32_t o = 0; o < 300; o += 3) {
            const glm::vec3 size = extent(boxes[o]);
            glm::vec3 lo = f % 10 < 5
                               ? glm::vec3(-25.0f + 0.5f * u(rng), 0.0f, -25.0f + 0.5f * u(rng))
                               : glm::vec3(30.0f * u(rng), 0.0f, 30.0f * u(rng));
            boxes[o] = {lo, lo + size};
            tree.reinsert(o, boxes[o]);
        }
        tree.refitDirtyBounds();
        read_back_device.beginFrame(vp, eye, boxes);
        read_back.cullAndRender(tree, testing::makeFrame(view, f, f / 30.0), read_back_device);
        device.beginFrame(vp, eye, boxes);
        gpu_driven.cullAndRender(tree, testing::makeFrame(view, f, f / 30.0), device);
        forgotten += gpu_driven.lastForgottenSlots().size();
        ASSERT_EQ(drawnFlags(device, boxes.size()), drawnFlags(read_back_device, boxes.size()))
            << "frame " << f;
        const std::vector<uint8_t> truth = device.groundTruth();
        const std::vector<uint8_t> drawn = drawnFlags(device, boxes.size());
        for (uint32_t o = 0; o < boxes.size(); ++o) {
            ASSERT_FALSE(truth[o] && !drawn[o]) << "frame " << f << " missed object " << o;
        }
    }
    EXPECT_GT(forgotten, 0u) << "the tree reused node indices";
}

// Each batch twice the one before, the last ending at the last unit; empty batches dropped.
TEST(GpuDrivenCuller, SecondPhaseBatchesDoubleAndEndAtTheLastUnit) {
    std::vector<uint32_t> ends;
    secondPhaseBatchEnds(15, 4, ends);
    EXPECT_EQ(ends, (std::vector<uint32_t>{1, 3, 7, 15}));
    secondPhaseBatchEnds(1500, 4, ends);
    EXPECT_EQ(ends, (std::vector<uint32_t>{100, 300, 700, 1500}));
    secondPhaseBatchEnds(100, 1, ends);
    EXPECT_EQ(ends, (std::vector<uint32_t>{100}));
    secondPhaseBatchEnds(100, 0, ends);
    EXPECT_EQ(ends, (std::vector<uint32_t>{100})) << "0 batches are one";
    secondPhaseBatchEnds(3, 4, ends);
    EXPECT_EQ(ends, (std::vector<uint32_t>{1, 3})) << "3 * 1/15 and 3 * 3/15 round to 0";
    secondPhaseBatchEnds(0, 4, ends);
    EXPECT_EQ(ends, (std::vector<uint32_t>{0}));
    secondPhaseBatchEnds(1000, 16, ends);
    EXPECT_EQ(ends.back(), 1000u);
    EXPECT_TRUE(std::is_sorted(ends.begin(), ends.end()));
    EXPECT_EQ(std::adjacent_find(ends.begin(), ends.end()), ends.end()) << "no empty batch";
}

// Called on a device without GPU-driven draws (a test looping over every culler), it draws
// everything in the frustum: never less than what is visible.
TEST(GpuDrivenCuller, OnADeviceWithoutTheCapabilityItDrawsTheFrustum) {
    const std::vector<Aabb> boxes = wallAndField();
    const BspTree tree = testing::buildTree(boxes, 2);
    ScriptedQueryDevice device;
    EXPECT_EQ(device.features() & kGpuDrivenDraws, 0u);
    GpuDrivenCuller culler(GpuDrivenOptions{});
    culler.reset(tree);
    const glm::vec3 eye(0, 2, 10), target(0, 2, -19);
    const CullFrame frame = testing::makeFrame(testing::makeView(eye, target), 0, 0.0);
    culler.cullAndRender(tree, frame, device);
    culler.afterFrame(device);
    uint64_t in_frustum = 0;
    for (const Aabb& box : boxes)
        in_frustum += classify(frame.view.frustum, box) != FrustumTest::Outside;
    EXPECT_EQ(device.counters().objects_drawn, in_frustum);
    EXPECT_EQ(culler.lastUnits(), 0u);
}

// `raster` on a device without GPU-driven draws or box rasterisation is refused before any work,
// with one line naming the culler and what is missing (the run exits 2 on it).
TEST(GpuDrivenCuller, RasterOnADeviceWithoutTheCapabilitiesIsRefusedWithOneLine) {
    const CullerRow* raster = findCuller("raster");
    ASSERT_NE(raster, nullptr);
    EXPECT_EQ(raster->device_needs, uint32_t{kGpuDrivenDraws | kBoxRaster});
    ScriptedQueryDevice scripted;
    try {
        requireDeviceFeatures(*raster, scripted.features());
        ADD_FAILURE() << "refused nothing";
    } catch (const RegistryError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "culler 'raster' needs GPU-driven draws (multi-draw indirect and storage "
                  "buffers) and box rasterisation (storage buffers written by fragment shaders), "
                  "which this device does not offer");
    }
    DepthRasterDevice capable(8, 8);
    EXPECT_NO_THROW(requireDeviceFeatures(*raster, capable.features()));
}

TEST(GpuDrivenCuller, TheSoftwareDeviceOffersBothTests) {
    DepthRasterDevice device(8, 8);
    EXPECT_EQ(device.features() & (kGpuDrivenDraws | kBoxRaster), kGpuDrivenDraws | kBoxRaster);
}

}  // namespace
}  // namespace occsim
