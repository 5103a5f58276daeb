// Micro-benchmarks of the CPU side of culling (no OpenGL): BSP build, reinsertion with refit and
// local adaptation, batch frustum classification, and a statistical-culler traversal on the
// scripted query device.
// Run: ./build/release/tests/benchmarks/bench_culling
#include <benchmark/benchmark.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "culling/cullers/statistical_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/geometry/frustum.h"
#include "occsim/culling/testing/scripted_query_device.h"
#include "occsim/culling/tree/bsp_tree.h"

namespace occsim {
namespace {

std::vector<Aabb> field(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> x(-35, 35), y(0, 8), z(-200, 0), size(1.0f, 2.5f);
    std::vector<Aabb> boxes;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 lo(x(rng), y(rng), z(rng));
        const float s = size(rng);
        boxes.push_back({lo, lo + glm::vec3(1.5f * s, s, 1.5f * s)});
    }
    return boxes;
}

void BM_BspBuild(benchmark::State& state) {
    const auto objects = static_cast<uint32_t>(state.range(0));
    const std::vector<Aabb> boxes = field(objects, 1);
    BspBuildOptions options;
    options.split_rule = state.range(1) != 0 ? BspSplitRule::Sah : BspSplitRule::Median;
    BspTree tree;
    for (auto _ : state) {
        tree.build(boxes, options);
        benchmark::DoNotOptimize(tree.nodeCount());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * objects);
}
BENCHMARK(BM_BspBuild)->Args({3000, 1})->Args({30000, 1})->Args({3000, 0})->Args({30000, 0});

// A fifth of the objects move every iteration (one frame: reinsert them, then refit and adapt),
// back and forth over 64 frames so that the tree reaches a steady state instead of watching its
// movers drift away.
void BM_BspReinsertMovedObjects(benchmark::State& state) {
    const auto objects = static_cast<uint32_t>(state.range(0));
    std::vector<Aabb> boxes = field(objects, 1);
    BspTree tree;
    BspBuildOptions options;
    options.split_rule = BspSplitRule::Sah;
    tree.build(boxes, options);
    const uint32_t movers = objects / 5;
    const glm::vec3 step(0.1f, 0.0f, -0.07f);
    uint64_t frame = 0;
    for (auto _ : state) {
        const glm::vec3 by = (frame++ / 64) % 2 == 0 ? step : -step;
        for (uint32_t o = 0; o < movers; ++o) {
            boxes[o].min += by;
            boxes[o].max += by;
            tree.reinsert(o, boxes[o]);
        }
        tree.refitDirtyBounds();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * movers);
    state.counters["walked/reinsert"] =
        static_cast<double>(tree.stats().nodes_walked) /
        static_cast<double>(std::max<uint64_t>(1, tree.stats().reinserts));
}
BENCHMARK(BM_BspReinsertMovedObjects)->Arg(3000)->Arg(30000);

void BM_FrustumClassifyBatch(benchmark::State& state) {
    const auto count = static_cast<size_t>(state.range(0));
    const std::vector<Aabb> boxes = field(static_cast<uint32_t>(count), 2);
    const testing::BoxColumns columns(boxes);
    const Frustum f = frustumFromViewProjection(
        glm::perspective(glm::radians(60.0f), 4.0f / 3.0f, 0.2f, 400.0f) *
        glm::lookAt(glm::vec3(0, 3, 8), glm::vec3(0, 2, -30), glm::vec3(0, 1, 0)));
    std::vector<FrustumTest> out(count);
    for (auto _ : state) {
        columns.classify(f, count, out.data());
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(count));
}
BENCHMARK(BM_FrustumClassifyBatch)->Arg(3000)->Arg(100000);

void BM_StatisticalTraversal(benchmark::State& state) {
    const std::vector<Aabb> boxes = field(3000, 3);
    BspTree tree;
    tree.build(boxes, BspBuildOptions{});
    std::vector<uint8_t> visible(boxes.size());
    for (size_t i = 0; i < visible.size(); i += 10) visible[i] = 1;
    ScriptedQueryDevice device(8);
    device.setVisibility(visible, boxes);
    StatisticalCuller culler;
    culler.reset(tree);
    CullFrame frame;
    frame.view.eye = glm::vec3(0, 3, 8);
    frame.view.frustum = frustumFromViewProjection(
        glm::perspective(glm::radians(60.0f), 4.0f / 3.0f, 0.2f, 400.0f) *
        glm::lookAt(frame.view.eye, glm::vec3(0, 2, -30), glm::vec3(0, 1, 0)));
    frame.view.near_radius = 0.3f;
    uint64_t index = 0;
    for (auto _ : state) {
        frame.frame_index = index;
        frame.time_s = static_cast<double>(index++) / 30.0;
        device.clearLog();
        culler.cullAndRender(tree, frame, device);
    }
}
BENCHMARK(BM_StatisticalTraversal);

}  // namespace
}  // namespace occsim

BENCHMARK_MAIN();
