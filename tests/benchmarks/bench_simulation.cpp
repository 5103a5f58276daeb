// Micro-benchmarks of the simulator's own work beside the rendering it measures
// (docs/performance.md): reinserting N movers against rebuilding the tree from scratch, the
// frustum test per box (one-off, with the frame's plane table, in a batch), the traversal's CPU
// per node for every culler, the mover update per object, and advancing one shared world per
// frame against one world per configuration.
// Run: ./build/release/tests/benchmarks/bench_simulation
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <random>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "occsim/culling/tree/bsp_tree.h"
#include "sim/run/shared_world.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"
#include "tests/support/culling_fixtures.h"

namespace occsim {
namespace {

constexpr uint32_t kFieldObjects = 100000;

// 100,000 small boxes over a 600 m x 600 m field, 10 m high.
std::vector<Aabb> bigField(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> xz(-300, 300), y(0, 10), size(0.3f, 2.0f);
    std::vector<Aabb> boxes;
    boxes.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 lo(xz(rng), y(rng), xz(rng));
        const float s = size(rng);
        boxes.push_back({lo, lo + glm::vec3(s, s, s)});
    }
    return boxes;
}

// Moves the first `movers` boxes one step (1 m/s at 30 frames a second, turning back every 64
// frames so the field keeps its shape).
void stepBoxes(std::vector<Aabb>& boxes, uint32_t movers, uint64_t frame) {
    const glm::vec3 v =
        (frame / 64) % 2 == 0 ? glm::vec3(0.033f, 0, -0.021f) : glm::vec3(-0.033f, 0, 0.021f);
    for (uint32_t o = 0; o < movers; ++o) {
        boxes[o].min += v;
        boxes[o].max += v;
    }
}

// One frame of N movers in a 100,000-object tree: reinsert each moved object, refit, adapt.
void BM_ReinsertMovers(benchmark::State& state) {
    const auto movers = static_cast<uint32_t>(state.range(0));
    std::vector<Aabb> boxes = bigField(kFieldObjects, 1);
    BspBuildOptions options;
    options.split_rule = BspSplitRule::Sah;
    BspTree tree;
    tree.build(boxes, options);
    uint64_t frame = 0;
    for (auto _ : state) {
        stepBoxes(boxes, movers, frame++);
        for (uint32_t o = 0; o < movers; ++o) tree.reinsert(o, boxes[o]);
        tree.refitDirtyBounds();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * movers);
    state.counters["in_place"] = static_cast<double>(tree.stats().reinserts_in_place) /
                                 static_cast<double>(std::max<uint64_t>(1, tree.stats().reinserts));
}
BENCHMARK(BM_ReinsertMovers)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// The same frames with the tree rebuilt from scratch after the movers moved: what reinsertion
// must beat.
void BM_RebuildTree(benchmark::State& state) {
    const auto movers = static_cast<uint32_t>(state.range(0));
    std::vector<Aabb> boxes = bigField(kFieldObjects, 1);
    BspBuildOptions options;
    options.split_rule = BspSplitRule::Sah;
    BspTree tree;
    uint64_t frame = 0;
    for (auto _ : state) {
        stepBoxes(boxes, movers, frame++);
        tree.build(boxes, options);
        benchmark::DoNotOptimize(tree.nodeCount());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * movers);
}
BENCHMARK(BM_RebuildTree)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// The frustum test per box, three ways over the same 30,000 boxes: 0 = classify(Frustum, box),
// which builds the plane table for every box (the cullers' path before issue 14); 1 = the
// production path, the table built once and the inline kernel per box, as the cullers call it
// per node and object; 2 = classifyBatch() over structure-of-arrays boxes.
void BM_FrustumClassifyPerBox(benchmark::State& state) {
    const int path = static_cast<int>(state.range(0));
    static const char* const kLabels[] = {"single, table per box", "single, table per frame",
                                          "batch, table per frame"};
    state.SetLabel(kLabels[path]);
    const std::vector<Aabb> boxes = bigField(30000, 5);
    const testing::BoxColumns columns(boxes);
    const Frustum f = frustumFromViewProjection(
        glm::perspective(glm::radians(60.0f), 4.0f / 3.0f, 0.2f, 1000.0f) *
        glm::lookAt(glm::vec3(0, 5, 250), glm::vec3(0, 2, 0), glm::vec3(0, 1, 0)));
    std::vector<FrustumTest> out(boxes.size());
    for (auto _ : state) {
        if (path == 0) {
            for (size_t i = 0; i < boxes.size(); ++i) out[i] = classify(f, boxes[i]);
        } else if (path == 1) {
            const FrustumPlanes table = planeTableOf(f);
            for (size_t i = 0; i < boxes.size(); ++i) out[i] = classify(table, boxes[i]);
        } else {
            columns.classify(planeTableOf(f), boxes.size(), out.data());
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.counters["ns_per_box"] = benchmark::Counter(
        static_cast<double>(boxes.size()) * static_cast<double>(state.iterations()),
        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_FrustumClassifyPerBox)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

// A device that answers at once and costs nothing: a query comes back hidden for one subject in
// ten (a hash of its tag), visible otherwise, ready after a fixed number of later commands. It
// lets the benchmark time the culler alone (the scripted test device scans every object per
// query).
class InstantDevice final : public RenderDevice {
  public:
    using RenderDevice::issueQuery;
    void drawObject(uint32_t) override {
        ++commands_;
        ++counters_.objects_drawn;
    }
    QueryId issueQuery(std::span<const Aabb>, std::span<const QueryTag> subjects) override {
        const uint32_t key = subjects.empty() ? 0 : subjects.front().index;
        const QueryId id = next_id_++ % kSlots;
        slots_[id] = {commands_++, (key * 2654435761u) % 10 == 0 ? 0u : 100u};
        ++counters_.queries_issued;
        return id;
    }
    bool isQueryReady(QueryId id) override { return commands_ - slots_[id].issued_at > 8; }
    QueryAnswer takeAnswer(QueryId id) override {
        return {slots_[id].samples > 0, slots_[id].samples, !isQueryReady(id)};
    }

  private:
    static constexpr uint32_t kSlots = 1u << 16;
    struct Slot {
        uint64_t issued_at = 0;
        uint64_t samples = 0;
    };
    std::vector<Slot> slots_ = std::vector<Slot>(kSlots);
    uint64_t commands_ = 0;
    uint32_t next_id_ = 0;
};

// One culler's frame over a 30,000-object tree with answers that cost nothing: the CPU the
// traversal and its decisions cost, per node whose bounds pass the frustum.
void BM_CullerTraversal(benchmark::State& state) {
    const CullerRow& algorithm = *cullerRows()[static_cast<size_t>(state.range(0))];
    state.SetLabel(std::string(algorithm.name));
    const std::vector<Aabb> boxes = bigField(30000, 3);
    BspTree tree;
    BspBuildOptions options;
    options.split_rule = BspSplitRule::Sah;
    tree.build(boxes, options);
    std::vector<uint8_t> visible(boxes.size(), 0);
    for (size_t i = 0; i < visible.size(); i += 10) visible[i] = 1;
    InstantDevice device;
    const auto culler = makeCuller(algorithm, CullerOptions{});
    culler->reset(tree);
    CullFrame frame;
    frame.view.eye = glm::vec3(0, 5, 250);
    frame.view.frustum = frustumFromViewProjection(
        glm::perspective(glm::radians(60.0f), 4.0f / 3.0f, 0.2f, 1000.0f) *
        glm::lookAt(frame.view.eye, glm::vec3(0, 2, 0), glm::vec3(0, 1, 0)));
    frame.view.near_radius =
        static_cast<float>(nearPlaneCornerDistance(0.2, glm::radians(60.0), 4.0 / 3.0));
    frame.ground_truth_visible = visible;
    uint32_t nodes_in_frustum = 0;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        if (tree.isLive(n) && !isEmpty(tree.bounds(n)) &&
            classify(frame.view.frustum, tree.bounds(n)) != FrustumTest::Outside) {
            ++nodes_in_frustum;
        }
    }
    uint64_t index = 0;
    for (auto _ : state) {
        frame.frame_index = index;
        frame.time_s = static_cast<double>(index++) / 30.0;
        culler->cullAndRender(tree, frame, device);
    }
    state.counters["nodes_in_frustum"] = nodes_in_frustum;
    state.counters["ns_per_node"] = benchmark::Counter(
        static_cast<double>(nodes_in_frustum) * static_cast<double>(state.iterations()),
        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CullerTraversal)
    ->DenseRange(0, static_cast<int64_t>(cullerRows().size()) - 1)
    ->Unit(benchmark::kMicrosecond);

// The movers' own update: every kind of motion stepping one frame, per object.
void BM_MoverUpdate(benchmark::State& state) {
    Scenario s;
    s.seed = 5;
    TeapotFieldSpec teapots;
    teapots.count = 20000;
    teapots.region = {glm::vec3(-200, 0, -200), glm::vec3(200, 10, 200)};
    teapots.tessellation = 1;
    SceneSourceSpec& source = s.sources.emplace_back();
    source.type = SourceType::Teapots;
    source.spec.emplace<TeapotFieldSpec>(teapots);
    for (MotionType motion :
         {MotionType::Bounce, MotionType::Orbit, MotionType::RandomWalk, MotionType::Spin}) {
        MoverSpec m;
        m.fraction = 0.25;
        m.motion = motion;
        s.movers.push_back(m);
    }
    s.camera.keyframes.push_back({});
    const Scene scene = buildScene(s);
    WorldState world = initialState(scene);
    for (auto _ : state) {
        stepMovers(scene, world, 1.0 / 30.0);
        benchmark::DoNotOptimize(world.boxes.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(world.movers.size()));
}
BENCHMARK(BM_MoverUpdate)->Unit(benchmark::kMicrosecond);

// The default teapots scenario's frames with its movers, advanced the way a bench of N
// configurations did before the world was shared (N worlds, each stepped every frame: Arg(7))
// and the way it does now (one world: Arg(1)). One iteration is every frame of the scenario;
// the worlds are built outside the timing. Counters: advance time per frame, and the update part
// of it (movers, reinsertion, refit: what FrameStats::update_ms measures) per frame.
void BM_WorldAdvance(benchmark::State& state) {
    const auto worlds = static_cast<size_t>(state.range(0));
    const Scenario scenario =
        parseScenarioFile(std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/teapots.json");
    const Scene scene = buildScene(scenario);
    double update_ms = 0.0;
    uint64_t frames = 0;
    for (auto _ : state) {
        state.PauseTiming();
        std::vector<std::unique_ptr<SharedWorld>> all;
        for (size_t w = 0; w < worlds; ++w)
            all.push_back(std::make_unique<SharedWorld>(scene, scenario));
        state.ResumeTiming();
        for (uint32_t f = 0; f < scenario.frames; ++f) {
            for (auto& world : all) world->advance();
        }
        state.PauseTiming();
        for (const auto& world : all) update_ms += world->updateMsTotal();
        frames += scenario.frames;
        all.clear();
        state.ResumeTiming();
    }
    state.counters["frames"] = static_cast<double>(scenario.frames);
    state.counters["movers"] = static_cast<double>(scene.initial_movers.size());
    state.counters["update_ms_per_frame"] =
        update_ms / static_cast<double>(std::max<uint64_t>(1, frames));
}
BENCHMARK(BM_WorldAdvance)->ArgName("worlds")->Arg(1)->Arg(7)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace occsim

BENCHMARK_MAIN();
