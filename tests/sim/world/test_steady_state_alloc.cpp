// Issue 14: the simulator's own work is nearly free, so in the steady state a frame allocates
// nothing. For every registered algorithm on every device in culling/, a moving scene (movers
// reinserted into the BSP tree each frame, the camera circling) runs a warm-up, and then the
// frames' cull and reinsert must make no heap allocation at all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "culling_fixtures.h"
#include "occsim/culling/devices/approximate_device.h"
#include "occsim/culling/devices/tracing_device.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/depth_raster_device.h"
#include "occsim/culling/testing/scripted_query_device.h"
#include "occsim/culling/tree/bsp_tree.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"

// Counts calls of the replaceable operator new while g_counting is set. The other forms (arrays,
// nothrow) call this one in libstdc++, so every container allocation passes here. GCC takes
// free() in a replacement operator delete for a mismatch with operator new once both are
// inlined; replacing them this way is what the standard allows, so that warning is off here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
namespace {
bool g_counting = false;
uint64_t g_allocations = 0;
}  // namespace

void* operator new(std::size_t size) {
    if (g_counting) ++g_allocations;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace occsim {
namespace {

constexpr uint32_t kObjects = 600;
constexpr uint32_t kMovers = 120;
// Movers and camera repeat their motion every kPeriod frames, so after a warm-up every buffer
// has met the largest frame it will meet.
constexpr uint64_t kPeriod = 24;
constexpr uint64_t kWarmUpFrames = 3 * kPeriod;
constexpr uint64_t kMeasuredFrames = 2 * kPeriod;

enum class DeviceKind {
    Scripted,         // ScriptedQueryDevice, answers at once
    ScriptedLatency,  // ScriptedQueryDevice, answers after 3 commands
    Approximate,      // ApproximateDevice (pixel threshold, stale results) over a scripted one
    Tracing,          // TracingDevice recording every frame, over a scripted one
    DepthRaster,      // DepthRasterDevice: a small depth raster of box cards
};

const char* nameOf(DeviceKind kind) {
    switch (kind) {
        case DeviceKind::Scripted:
            return "scripted";
        case DeviceKind::ScriptedLatency:
            return "scripted_latency";
        case DeviceKind::Approximate:
            return "approximate";
        case DeviceKind::Tracing:
            return "tracing";
        case DeviceKind::DepthRaster:
            return "depth_raster";
    }
    return "?";
}

// The scene at frame f: the first kMovers boxes move on circles of radius 6 m (each its own
// phase), so they cross cells, leave nodes and come back; the rest stand still.
void placeBoxes(const std::vector<Aabb>& initial, uint64_t f, std::vector<Aabb>& out) {
    const float turn = 6.2831853f * static_cast<float>(f % kPeriod) / static_cast<float>(kPeriod);
    for (uint32_t o = 0; o < kMovers; ++o) {
        const float phase = turn + 0.37f * static_cast<float>(o);
        const glm::vec3 offset(6.0f * std::cos(phase), 0.0f, 6.0f * std::sin(phase));
        out[o] = {initial[o].min + offset, initial[o].max + offset};
    }
}

struct Camera {
    CullView view;
    glm::mat4 view_projection{1.0f};
};

// The camera circles the field's centre at 60 m, looking across it.
Camera cameraAt(uint64_t f) {
    const float angle = 6.2831853f * static_cast<float>(f % kPeriod) / static_cast<float>(kPeriod);
    const glm::vec3 eye(60.0f * std::cos(angle), 8.0f, 60.0f * std::sin(angle));
    Camera c;
    c.view = testing::makeView(eye, glm::vec3(0.0f));
    c.view_projection = glm::perspective(glm::radians(60.0f), 4.0f / 3.0f, 0.1f, 1000.0f) *
                        glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
    return c;
}

class SteadyStateAllocation : public ::testing::TestWithParam<std::tuple<size_t, DeviceKind>> {};

TEST_P(SteadyStateAllocation, CullAndReinsertAllocateNothing) {
    const CullerRow& algorithm = *cullerRows()[std::get<0>(GetParam())];
    const DeviceKind kind = std::get<1>(GetParam());

    const std::vector<Aabb> initial = testing::randomBoxes(kObjects, 17, 60.0f);
    std::vector<Aabb> boxes = initial;
    BspTree tree = testing::buildTree(boxes);
    // Every part of every culler: a cost model and triangle counts (statistical+), ground truth
    // (the oracle), approximation (the devices that apply it).
    CullerOptions options;
    options.cost_model = {0.01, 5e-5, 0.005};
    const std::vector<uint32_t> triangles(kObjects, 1000);
    std::vector<uint8_t> visible(kObjects, 0);
    for (uint32_t o = 0; o < kObjects; o += 4) visible[o] = 1;

    ScriptedQueryDevice scripted(kind == DeviceKind::ScriptedLatency ? 3 : 0);
    // The scripted device's samples count the visible objects a query hits: a threshold of one
    // hides single hits and keeps the rest.
    ApproximateDevice approximate(scripted, ApproximationOptions{1, true});
    TracingDevice tracing(scripted);
    DepthRasterDevice raster(64, 48, 2);
    RenderDevice* device = &scripted;
    if (kind == DeviceKind::Approximate) device = &approximate;
    if (kind == DeviceKind::Tracing) device = &tracing;
    if (kind == DeviceKind::DepthRaster) device = &raster;
    // A run refuses a culler on a device without what it needs (requireDeviceFeatures): such a
    // pair never runs, so there is nothing to measure.
    if ((algorithm.device_needs & ~device->features()) != 0) {
        GTEST_SKIP() << algorithm.name << " needs what this device withholds";
    }

    const std::unique_ptr<Culler> culler = makeCuller(algorithm, options);
    culler->reset(tree);

    // Counted apart, so that a failure says which side allocated.
    uint64_t first_frame = 0, measured_tree = 0, measured_cull = 0;
    for (uint64_t f = 0; f < kWarmUpFrames + kMeasuredFrames; ++f) {
        g_allocations = 0;
        g_counting = true;
        // What a frame of the simulation does: move, reinsert, refit, set up the device, cull.
        placeBoxes(initial, f, boxes);
        for (uint32_t o = 0; o < kMovers; ++o) tree.reinsert(o, boxes[o]);
        tree.refitDirtyBounds();
        const uint64_t tree_allocations = g_allocations;
        const Camera camera = cameraAt(f);
        if (kind == DeviceKind::DepthRaster) {
            raster.beginFrame(camera.view_projection, camera.view.eye, boxes);
        } else {
            scripted.updateVisibility(visible, boxes);
            scripted.clearLog();
        }
        if (kind == DeviceKind::Tracing) tracing.beginTrace(f);
        CullFrame frame = testing::makeFrame(camera.view, f, static_cast<double>(f) / 30.0);
        frame.object_triangles = triangles;
        frame.ground_truth_visible = visible;
        culler->cullAndRender(tree, frame, *device);
        g_counting = false;
        if (f == 0) first_frame = g_allocations;
        if (f >= kWarmUpFrames) {
            measured_tree += tree_allocations;
            measured_cull += g_allocations - tree_allocations;
        }
    }
    EXPECT_GT(first_frame, 0u) << "the counter sees the first frame sizing its buffers";
    EXPECT_GT(device->counters().objects_drawn, 0u);
    if (algorithm.issues_queries) {
        EXPECT_GT(device->counters().queries_issued, 0u);
    }
    EXPECT_GT(tree.stats().reinserts_moved, 0u) << "the movers must change nodes";
    EXPECT_EQ(measured_tree, 0u) << "reinsert and refit allocated " << measured_tree << " times in "
                                 << kMeasuredFrames << " steady frames";
    EXPECT_EQ(measured_cull, 0u) << algorithm.name << " on the " << nameOf(kind)
                                 << " device allocated " << measured_cull << " times in "
                                 << kMeasuredFrames << " steady frames";
}

// A world with glTF animations (issue 22): a grid of BoxAnimated copies playing their animations
// at seeded phases, a fifth of the copies spinning whole, teapots orbiting. After a warm-up, the
// world's step (movers, every copy posed through its hierarchy, boxes) and the tree's reinsert
// and refit allocate nothing, and neither does a culler on that tree.
TEST(SteadyStateAllocationWithAnimations, StepPoseReinsertAndCullAllocateNothing) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("occsim-alloc-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string box = (std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios" / "assets" /
                             "BoxAnimated" / "BoxAnimated.gltf")
                                .string();
    std::ofstream(dir / "animated.json") << R"({"format_version": 1, "name": "animated", "seed": 3,
      "camera": {"keyframes": [{"time": 0, "position": [0, 3, 30], "target": [0, 0, 0]}]},
      "scene": {"sources": [
        {"type": "gltf", "path": ")" << box
                                         << R"(", "offset": [-10, 0, -10],
         "replicate": {"mode": "grid", "count_x": 6, "count_z": 6, "spacing": 4},
         "animation": {"random_phase": true}},
        {"type": "teapots", "count": 40, "region": {"min": [-12, 0, -12], "max": [12, 2, 12]}}]},
      "movers": [{"source": 0, "fraction": 0.2, "whole_copies": true, "motion": "spin"},
                 {"source": 1, "fraction": 0.5, "motion": "orbit", "speed": [1, 2]}]})";
    const Scenario scenario = parseScenarioFile(dir / "animated.json");
    std::filesystem::remove_all(dir);
    const Scene scene = buildScene(scenario);
    WorldState state = initialState(scene);
    ASSERT_GT(state.copies.size(), 0u);
    BspTree tree;
    tree.build(state.boxes, scenario.bsp);
    ScriptedQueryDevice device(3);
    std::vector<uint8_t> visible(scene.objectCount(), 0);
    for (uint32_t o = 0; o < scene.objectCount(); o += 3) visible[o] = 1;
    const std::unique_ptr<Culler> culler = makeCuller(*findCuller("chc++"), CullerOptions{});
    culler->reset(tree);
    const CullView view = testing::makeView(glm::vec3(0, 3, 30), glm::vec3(0.0f));
    constexpr uint64_t kWarmUp = 600, kMeasured = 200;  // 20 s of warm-up at 30 frames per second
    uint64_t measured = 0;
    for (uint64_t f = 0; f < kWarmUp + kMeasured; ++f) {
        g_allocations = 0;
        g_counting = true;
        stepMovers(scene, state, 1.0 / 30.0);
        for (const uint32_t o : state.moved) tree.reinsert(o, state.boxes[o]);
        tree.refitDirtyBounds();
        device.updateVisibility(visible, state.boxes);
        device.clearLog();
        culler->cullAndRender(tree, testing::makeFrame(view, f, static_cast<double>(f) / 30.0),
                              device);
        g_counting = false;
        if (f >= kWarmUp) measured += g_allocations;
    }
    g_allocations = 0;
    g_counting = true;
    const WorldState copy = state;
    g_counting = false;
    EXPECT_GT(g_allocations, 0u) << "the counter sees a world's buffers being allocated";
    EXPECT_GT(state.moved.size(), 36u)
        << "every copy's inner box, the spinning copies, the teapots";
    EXPECT_GT(tree.stats().reinserts_moved, 0u);
    EXPECT_EQ(measured, 0u) << "an animated world allocated " << measured << " times in "
                            << kMeasured << " steady frames";
}

INSTANTIATE_TEST_SUITE_P(
    EveryAlgorithmAndDevice, SteadyStateAllocation,
    ::testing::Combine(::testing::Range<size_t>(0, cullerRows().size()),
                       ::testing::Values(DeviceKind::Scripted, DeviceKind::ScriptedLatency,
                                         DeviceKind::Approximate, DeviceKind::Tracing,
                                         DeviceKind::DepthRaster)),
    [](const ::testing::TestParamInfo<std::tuple<size_t, DeviceKind>>& param_info) {
        std::string name(cullerRows()[std::get<0>(param_info.param)]->name);
        for (char& c : name) {
            if (c == '+') c = 'p';
            if (c == '-') c = '_';
        }
        return name + "_" + nameOf(std::get<1>(param_info.param));
    });

}  // namespace
}  // namespace occsim
