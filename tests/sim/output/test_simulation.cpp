// End to end headless (EGL by default): the small teapot scenario, every algorithm, ground truth
// and error; and the same bench on every backend the build has.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

#include "culling_fixtures.h"
#include "headless_backends.h"
#include "sim/output/report.h"
#include "sim/world/scene_info.h"
#include "small_bench.h"

namespace occsim {
namespace {

using testing::benchSmall;
using testing::freshDir;
using testing::kSmall;
using testing::traitsOf;

TEST(Simulation, ConservativeAlgorithmsAndIdealShowZeroErrorPixelsOnEveryFrame) {
    std::vector<std::string> conservative;
    for (const std::string& name : cullerNames()) {
        if (name != "async") conservative.push_back(name);  // per-object async may miss by design
    }
    const BenchResult result = benchSmall(true, LatencyMode{}, conservative);
    ASSERT_EQ(result.runs.size(), conservative.size());
    for (const RunRecord& run : result.runs) {
        ASSERT_EQ(run.frames.size(), 40u);
        for (const FrameStats& f : run.frames) {
            EXPECT_EQ(f.error_pixels, 0) << run.summary.label << " frame " << f.frame;
            EXPECT_EQ(f.missed_objects, 0) << run.summary.label << " frame " << f.frame;
            EXPECT_GT(f.visible_objects, 0);
        }
    }
}

// ideal-box is the limit of culling by boxes: Ideal draws no more than it, and no conservative
// culler that decides by boxes against the depth so far (which is never nearer than the frame's
// final depth) draws less, frame by frame.
TEST(Simulation, IdealBoxLiesBetweenIdealAndEveryConservativeCuller) {
    const std::vector<std::string> names = {"vfc",   "stop-and-wait", "statistical", "statistical+",
                                            "chc",   "chc++",         "hzb",         "masked",
                                            "ideal", "ideal-box"};
    const BenchResult result = benchSmall(true, LatencyMode{true, 8}, names);
    const RunRecord& box = result.runs.back();
    ASSERT_EQ(box.summary.label, "ideal-box");
    uint64_t beyond_ideal = 0;
    for (const RunRecord& run : result.runs) {
        for (size_t f = 0; f < run.frames.size(); ++f) {
            const uint64_t limit = box.frames[f].objects_drawn;
            if (run.summary.label == "ideal") {
                EXPECT_LE(run.frames[f].objects_drawn, limit) << "frame " << f;
                beyond_ideal += limit - run.frames[f].objects_drawn;
            } else {
                EXPECT_GE(run.frames[f].objects_drawn, limit)
                    << run.summary.label << " frame " << f;
            }
        }
    }
    EXPECT_GT(beyond_ideal, 0u) << "boxes cost something on the teapots";
    EXPECT_EQ(box.summary.error_pixels_total, 0);
    EXPECT_EQ(box.summary.missed_objects_total, 0);
}

TEST(Simulation, GroundTruthIsIndependentOfTheCullersFrustumTest) {
    BenchOptions options;
    options.algorithms = traitsOf({"vfc"});
    options.measure_error = true;
    options.frames = 12;
    options.make_culler = [](const CullerRow&, const CullerOptions&) {
        return std::unique_ptr<Culler>(new testing::ShrunkenFrustumCuller);
    };
    const BenchResult result = runBenchmark(parseScenarioFile(kSmall), options);
    EXPECT_GT(result.runs[0].summary.error_pixels_total, 0) << "the dropped edge objects show";
    EXPECT_GT(result.runs[0].summary.missed_objects_total, 0);
}

// A culler that throws in its frame `fail_at`, culling like `inner` before it.
class FailingCuller final : public Culler {
  public:
    FailingCuller(std::unique_ptr<Culler> inner, uint32_t fail_at)
        : inner_(std::move(inner)), fail_at_(fail_at) {}
    void reset(const BspTree& tree) override { inner_->reset(tree); }
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override {
        if (frames_++ == fail_at_) throw std::runtime_error("out of budget");
        inner_->cullAndRender(tree, frame, device);
    }

  private:
    std::unique_ptr<Culler> inner_;
    uint32_t fail_at_;
    uint32_t frames_ = 0;
};

// The failure is named, not thrown: every configuration keeps the whole frames before it (those
// that rendered the failed frame first, in the rotated order too, drop it), and no repetition
// after it runs.
TEST(Simulation, AConfigurationThatThrowsEndsTheRunWithTheWholeFramesBeforeItNamed) {
    BenchOptions options;
    options.algorithms = traitsOf({"vfc", "chc", "statistical"});
    options.frames = 12;
    options.repetitions = 2;
    options.frame_order = FrameOrder::rotated;
    options.make_culler = [](const CullerRow& algorithm, const CullerOptions& culler) {
        std::unique_ptr<Culler> made = makeCuller(algorithm, culler);
        if (algorithm.name == "chc")
            return std::unique_ptr<Culler>(new FailingCuller(std::move(made), 5));
        return made;
    };
    const BenchResult result = runBenchmark(parseScenarioFile(kSmall), options);
    ASSERT_TRUE(result.partial.has_value());
    EXPECT_EQ(result.partial->reason, "configuration 'chc' failed at frame 5: out of budget");
    EXPECT_EQ(result.partial->signal, 0);
    EXPECT_EQ(result.partial->frames_reached, 5u);
    for (const RunRecord& run : result.runs) {
        EXPECT_EQ(run.frames.size(), 5u) << run.summary.label;
        EXPECT_EQ(run.repetitions.size(), 1u) << run.summary.label;
        EXPECT_EQ(run.summary.frames, 5u) << run.summary.label;
    }
    EXPECT_NE(partialLine(result).find("after 5 of 12 frames; the 5 whole frames are reported"),
              std::string::npos)
        << partialLine(result);
}

TEST(Simulation, CullersDrawFewerObjectsThanVfcAndIdealDrawsFewestWithNoQueries) {
    const BenchResult result = benchSmall(true, LatencyMode{true, 8});
    const auto& runs = result.runs;
    auto by = [&](const std::string& name) -> const RunSummary& {
        for (const RunRecord& r : runs) {
            if (r.summary.label == name) return r.summary;
        }
        throw std::runtime_error("no run " + name);
    };
    EXPECT_EQ(by("vfc").queries_mean, 0.0);
    EXPECT_EQ(by("ideal").queries_mean, 0.0);
    EXPECT_GT(by("stop-and-wait").queries_mean, by("statistical").queries_mean);
    EXPECT_LT(by("statistical").objects_mean, by("vfc").objects_mean);
    EXPECT_LT(by("stop-and-wait").objects_mean, by("vfc").objects_mean);
    EXPECT_LE(by("ideal").objects_mean, by("stop-and-wait").objects_mean);
}

// Over-draw is what a culler drew that ground truth does not see: every drawn object is either
// visible (and not missed) or over-drawn; Ideal over-draws nothing, VFC a great deal.
TEST(Simulation, OverdrawCountsTheObjectsDrawnThatGroundTruthDoesNotSee) {
    const BenchResult result =
        benchSmall(true, LatencyMode{true, 8}, {"vfc", "statistical", "async", "ideal"});
    const Scene scene = buildScene(parseScenarioFile(kSmall));
    const uint64_t teapot = scene.meshes[scene.object_mesh[0]].triangleCount();
    for (const RunRecord& run : result.runs) {
        double overdrawn = 0;
        for (const FrameStats& f : run.frames) {
            EXPECT_EQ(static_cast<int64_t>(f.objects_drawn),
                      f.visible_objects - f.missed_objects + f.overdrawn_objects)
                << run.summary.label << " frame " << f.frame;
            EXPECT_LE(f.overdrawn_triangles, static_cast<int64_t>(f.triangles));
            EXPECT_EQ(static_cast<uint64_t>(f.overdrawn_triangles),
                      teapot * static_cast<uint64_t>(f.overdrawn_objects))
                << "every object is a teapot of one tessellation";
            overdrawn += static_cast<double>(f.overdrawn_objects);
        }
        EXPECT_DOUBLE_EQ(run.summary.overdrawn_objects_mean,
                         overdrawn / static_cast<double>(run.frames.size()));
        if (run.summary.label == "ideal") {
            EXPECT_EQ(run.summary.overdrawn_objects_mean, 0.0);
        }
        if (run.summary.label == "vfc") {
            EXPECT_GT(run.summary.overdrawn_objects_mean, 10.0);
        }
    }
    const ComparisonTable table = comparisonTable(result.runs);
    EXPECT_NE(std::find(table.header.begin(), table.header.end(), "overdrawn/fr"),
              table.header.end());
    EXPECT_NE(std::find(table.header.begin(), table.header.end(), "overdrawn tris/fr"),
              table.header.end());
    EXPECT_NE(framesCsv(result.runs).find(",stray_pixels,overdrawn_objects,overdrawn_triangles,"),
              std::string::npos);
}

// conditional submits every object in the frustum and the device skips the hidden ones: the two
// are counted apart. With GL_QUERY_WAIT a draw executes exactly when its query passed samples,
// so the executed draws are the drawn set error measurement reads from those samples.
TEST(Simulation, ConditionalDrawsAreCountedAsSubmittedAndAsExecuted) {
    const Scenario scenario = parseScenarioFile(kSmall);
    BenchOptions options;
    options.measure_error = true;
    options.latency = LatencyMode{true, 8};
    options.frames = 12;
    const CullerRow& conditional = *findCuller("conditional");
    RunConfig waited{"conditional wait=true", &conditional, scenario.culler};
    waited.culler.edit(conditional).set("wait", 1.0);
    options.configs = {RunConfig{"vfc", findCuller("vfc"), scenario.culler},
                       RunConfig{"conditional", &conditional, scenario.culler}, waited};
    options.algorithms = {findCuller("vfc")};
    const BenchResult result = runBenchmark(scenario, options);
    ASSERT_EQ(result.runs.size(), 3u);
    bool skipped_some = false;
    for (const RunRecord& run : result.runs) {
        for (const FrameStats& f : run.frames) {
            EXPECT_LE(f.executed_objects, f.objects_drawn);
            EXPECT_LE(f.executed_triangles, f.triangles);
            if (run.summary.label == "vfc") {
                EXPECT_EQ(f.executed_objects, f.objects_drawn);
                EXPECT_EQ(f.executed_triangles, f.triangles);
            }
            if (run.summary.label == "conditional wait=true") {
                EXPECT_EQ(static_cast<int64_t>(f.executed_objects),
                          f.visible_objects - f.missed_objects + f.overdrawn_objects)
                    << "frame " << f.frame;
                skipped_some |= f.executed_objects < f.objects_drawn;
            }
        }
    }
    EXPECT_TRUE(skipped_some) << "the teapot field hides some of what is in the frustum";
    EXPECT_LT(result.runs[2].summary.executed_objects_mean, result.runs[2].summary.objects_mean);
    const ComparisonTable table = comparisonTable(result.runs);
    EXPECT_NE(std::find(table.header.begin(), table.header.end(), "exec objs/fr"),
              table.header.end());
}

TEST(Simulation, MovingObjectsAreReinsertedIntoOtherNodes) {
    const BenchResult result = benchSmall(false, LatencyMode{}, {"vfc"});
    uint64_t changes = 0;
    for (const FrameStats& f : result.runs[0].frames) {
        EXPECT_EQ(f.moved_objects, f.frame == 0 ? 0u : 90u);  // 20% + 10% of 300
        changes += f.node_changes;
    }
    EXPECT_GT(changes, 0u);
}

TEST(Simulation, DeterministicLatencyGivesIdenticalDecisionsOverThreeRuns) {
    std::vector<std::vector<std::pair<uint64_t, uint64_t>>> counts;
    for (int run = 0; run < 3; ++run) {
        const BenchResult r = benchSmall(false, LatencyMode{true, 6}, {"statistical"});
        counts.emplace_back();
        for (const FrameStats& f : r.runs[0].frames)
            counts.back().push_back({f.queries, f.objects_drawn});
    }
    EXPECT_EQ(counts[0], counts[1]);
    EXPECT_EQ(counts[0], counts[2]);
}

// The backend is where frames are rendered, not what the cullers decide: in deterministic-latency
// mode every algorithm issues the same queries and draws the same objects on each backend, frame
// by frame, and the run records which backend it was.
TEST(Simulation, EveryBackendGivesTheSameDeterministicCounts) {
    const std::vector<Backend> backends = testing::testedBackends();
    if (backends.size() < 2) GTEST_SKIP() << "this build has one headless backend (no OSMesa)";
    std::vector<std::vector<std::vector<std::pair<uint64_t, uint64_t>>>>
        counts;  // [backend][config][frame]
    for (Backend backend : backends) {
        BenchOptions options;
        options.algorithms = traitsOf(cullerNames());
        options.latency = LatencyMode{true, 6};
        options.backend.backend = backend;
        options.frames = 20;
        const BenchResult r = runBenchmark(parseScenarioFile(kSmall), options);
        EXPECT_EQ(r.metadata.backend, backendName(backend));
        counts.emplace_back();
        for (const RunRecord& run : r.runs) {
            counts.back().emplace_back();
            for (const FrameStats& f : run.frames)
                counts.back().back().push_back({f.queries, f.objects_drawn});
        }
    }
    uint64_t queries = 0;
    for (const auto& config : counts[0]) {
        for (const auto& frame : config) queries += frame.first;
    }
    EXPECT_GT(queries, 0u);
    for (size_t b = 1; b < counts.size(); ++b)
        EXPECT_EQ(counts[b], counts[0]) << backendName(backends[b]);
}

// GPU time is measured only where it means something: on llvmpipe every frame's gpu_ms and the
// summary's are -1 (n/a, null), and a run that times anyway (as on a GPU) fills them.
TEST(Simulation, GpuTimeIsMeasuredOnlyWhereMeaningful) {
    const BenchResult r = benchSmall(false, LatencyMode{true, 6}, {"chc"});
    ASSERT_FALSE(r.metadata.gpu_time_meaningful) << r.metadata.gl_renderer;
    for (const FrameStats& f : r.runs[0].frames) EXPECT_EQ(f.gpu_ms, -1.0);
    EXPECT_EQ(r.runs[0].summary.gpu_ms_mean, -1.0);

    const Scenario scenario = parseScenarioFile(kSmall);
    const Scene scene = buildScene(scenario);
    auto context = createHeadlessContext({}, scenario.width, scenario.height);
    GlRenderer renderer(scenario.width, scenario.height);
    uploadScene(scene, renderer);
    SimulationOptions options;
    options.measure_gpu_time = true;
    const CullerRow& chc = *findCuller("chc");
    Simulation sim(scene, scenario, chc, makeCuller(chc, scenario.culler), scenario.culler,
                   renderer, options);
    for (int f = 0; f < 3; ++f) EXPECT_GE(sim.renderFrame().gpu_ms, 0.0);
}

// Answer latency per run: in deterministic-latency mode with N, an answer polled ready had at
// least N commands after its query, one waited for fewer; every answer of the timed frames is
// counted once, and the per-frame counts add up to the run's.
TEST(Simulation, AnswerLatenciesAreSummarisedOverTheTimedFrames) {
    const BenchResult r = benchSmall(false, LatencyMode{true, 6}, {"chc", "vfc"});
    const RunRecord& chc = r.runs[0];
    const RunSummary& s = chc.summary;
    uint64_t answers = 0;
    for (const FrameStats& f : chc.frames) {
        if (f.frame >= parseScenarioFile(kSmall).warmup_frames) answers += f.answers;
        EXPECT_EQ(f.answers > 0, f.answer_latency_median >= 0.0) << f.frame;
    }
    EXPECT_GT(s.answers, 0u);
    EXPECT_EQ(s.answers, answers);
    EXPECT_GE(s.answer_latency_p95, s.answer_latency_median);
    EXPECT_LE(s.answer_latency_median, 6.0 + 1.0);
    EXPECT_EQ(r.runs[1].summary.answers, 0u);  // vfc issues no query
    EXPECT_EQ(r.runs[1].summary.answer_latency_median, -1.0);
}

TEST(FrameStats, AnswerLatencyRanksAreNearestRankOverTheHistogram) {
    RunSummary s;
    addAnswerLatencies(s, {0, 10, 0, 8, 2});  // 10 x 1, 8 x 3, 2 x 4
    EXPECT_EQ(s.answers, 20u);
    EXPECT_EQ(s.answer_latency_median, 1.0);  // rank 10
    EXPECT_EQ(s.answer_latency_p95, 4.0);     // rank 19
    addAnswerLatencies(s, {});
    EXPECT_EQ(s.answer_latency_median, -1.0);
    std::vector<uint32_t> frame = {7, 1, 3, 5};
    EXPECT_EQ(medianLatency(frame), 4.0);
}

// Frame orders (sim/run/frame_order.h): rotated renders configuration (f + k) mod n k-th,
// balanced a Williams design's row f; every configuration keeps its own figures whatever the
// order (decisions made reproducible).
TEST(Simulation, EveryFrameOrderGivesEveryConfigurationItsPlacesAndTheSameFigures) {
    std::vector<std::vector<std::vector<std::pair<uint64_t, uint64_t>>>>
        counts;  // [order][config][frame]
    for (const FrameOrder frame_order :
         {FrameOrder::fixed, FrameOrder::rotated, FrameOrder::balanced}) {
        BenchOptions options;
        options.algorithms = traitsOf({"vfc", "statistical", "chc"});
        options.latency = LatencyMode{true, 6};
        options.frames = 6;
        options.frame_order = frame_order;
        std::vector<std::string> order;
        options.on_frame = [&order](const FrameEvent& e) { order.push_back(e.config.label); };
        const BenchResult r = runBenchmark(parseScenarioFile(kSmall), options);
        ASSERT_EQ(order.size(), 18u);
        if (frame_order == FrameOrder::rotated) {
            const std::vector<std::string> expected = {
                "vfc", "statistical", "chc",         "statistical", "chc",         "vfc",
                "chc", "vfc",         "statistical", "vfc",         "statistical", "chc"};
            EXPECT_EQ(std::vector<std::string>(order.begin(), order.begin() + 12), expected);
        }
        if (frame_order == FrameOrder::balanced) {
            const std::vector<std::string> expected = {
                "vfc", "statistical", "chc",         "statistical", "chc",         "vfc",
                "chc", "vfc",         "statistical", "chc",         "statistical", "vfc",
                "vfc", "chc",         "statistical", "statistical", "vfc",         "chc"};
            EXPECT_EQ(order, expected);
        }
        counts.emplace_back();
        for (const RunRecord& run : r.runs) {
            counts.back().emplace_back();
            for (const FrameStats& f : run.frames)
                counts.back().back().push_back({f.queries, f.objects_drawn});
        }
    }
    EXPECT_EQ(counts[0], counts[1]);
    EXPECT_EQ(counts[0], counts[2]);
}

// Each of the six orders of three configurations, rendered fixed (so that each order puts every
// configuration after another one), gives each configuration the same decisions frame by frame
// in deterministic-latency mode: which culler follows which changes no decision.
TEST(Simulation, EveryPermutationOfThreeConfigurationsGivesEachTheSameDecisions) {
    std::vector<std::string> names = {"chc", "statistical", "vfc"};  // sorted
    std::map<std::string, std::vector<std::pair<uint64_t, uint64_t>>> first;
    do {
        BenchOptions options;
        options.algorithms = traitsOf(names);
        options.latency = LatencyMode{true, 6};
        options.frames = 6;
        options.frame_order = FrameOrder::fixed;
        const BenchResult r = runBenchmark(parseScenarioFile(kSmall), options);
        for (const RunRecord& run : r.runs) {
            std::vector<std::pair<uint64_t, uint64_t>> counts;
            for (const FrameStats& f : run.frames) counts.push_back({f.queries, f.objects_drawn});
            const auto [it, inserted] = first.emplace(run.summary.label, counts);
            if (!inserted) {
                EXPECT_EQ(counts, it->second) << run.summary.label << " in the order " << names[0]
                                              << "," << names[1] << "," << names[2];
            }
        }
    } while (std::next_permutation(names.begin(), names.end()));
    EXPECT_EQ(first.size(), 3u);
}

TEST(Simulation, DescribeReportsObjectsTrianglesMoversAndTree) {
    std::vector<std::string> warnings;
    const std::string text = describeScenario(parseScenarioFile(kSmall), warnings);
    EXPECT_NE(text.find("objects       300"), std::string::npos) << text;
    EXPECT_NE(text.find("movers        90"), std::string::npos) << text;
    EXPECT_NE(text.find("bsp "), std::string::npos) << text;
    EXPECT_TRUE(warnings.empty());
}

}  // namespace
}  // namespace occsim
