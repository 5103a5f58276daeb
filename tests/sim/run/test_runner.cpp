// runBenchmark (sim/run/runner.h) on the small teapot scenario, headless: a configuration's frame
// time does not depend on its place in --algos (a scripted clock charges work left behind), the
// configurations share one world stepped once a frame and decide as they do alone, ground truth is
// rendered only when something needs it, and the run writes no file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>

#include "small_bench.h"

namespace occsim {
namespace {

using testing::kSmall;
using testing::traitsOf;

// A culler that leaves work behind for whichever configuration renders next in the same frame
// (as vfc's heavy frame did on llvmpipe): the scripted clock charges that one 50 ms. Each reading
// of the clock is 1 ms after the one before, so that frame times are the same whatever the load.
double g_frame_clock_ms = 0.0;
double g_left_behind_ms = 0.0;
uint64_t g_left_in_frame = UINT64_MAX;
double scriptedFrameClockMs() { return g_frame_clock_ms += 1.0; }

class LeavingWorkCuller final : public Culler {
  public:
    LeavingWorkCuller(std::unique_ptr<Culler> inner, bool leaves)
        : inner_(std::move(inner)), leaves_(leaves) {}
    void reset(const BspTree& tree) override { inner_->reset(tree); }
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override {
        if (g_left_in_frame == frame.frame_index) g_frame_clock_ms += g_left_behind_ms;
        g_left_behind_ms = 0.0;
        inner_->cullAndRender(tree, frame, device);
        if (leaves_) {
            g_left_behind_ms = 50.0;
            g_left_in_frame = frame.frame_index;
        }
    }

  private:
    std::unique_ptr<Culler> inner_;
    bool leaves_;
};

// Mean frame time per configuration of a 12-frame run of `algos` in `order`, on the scripted clock
// with vfc leaving work behind.
std::map<std::string, double> meansWithVfcLeavingWork(const std::vector<std::string>& algos,
                                                      FrameOrder order) {
    g_frame_clock_ms = 0.0;
    g_left_behind_ms = 0.0;
    g_left_in_frame = UINT64_MAX;
    BenchOptions options;
    options.algorithms = traitsOf(algos);
    options.latency = LatencyMode{true, 6};
    // Two periods of the balanced order of three measured, after the warm-up frames.
    options.frames = parseScenarioFile(kSmall).warmup_frames + 12;
    options.frame_order = order;
    options.frame_clock_ms = scriptedFrameClockMs;
    options.make_culler = [](const CullerRow& algorithm, const CullerOptions& culler) {
        return std::unique_ptr<Culler>(
            new LeavingWorkCuller(makeCuller(algorithm, culler), algorithm.name == "vfc"));
    };
    const BenchResult r = runBenchmark(parseScenarioFile(kSmall), options);
    std::map<std::string, double> means;
    for (const RunRecord& run : r.runs) means[run.summary.label] = run.summary.frame_ms.mean;
    return means;
}

// Swapping two configurations in --algos changes neither's mean frame time in the default order;
// in the fixed order the one typed after vfc pays for vfc's work every frame.
TEST(Simulation, AConfigurationsFrameTimeDoesNotDependOnItsPlaceInAlgos) {
    const auto a = meansWithVfcLeavingWork({"vfc", "chc", "statistical"}, FrameOrder::balanced);
    const auto b = meansWithVfcLeavingWork({"vfc", "statistical", "chc"}, FrameOrder::balanced);
    for (const char* name : {"vfc", "chc", "statistical"}) {
        EXPECT_DOUBLE_EQ(a.at(name), b.at(name)) << name;
    }
    const auto fixed_a = meansWithVfcLeavingWork({"vfc", "chc", "statistical"}, FrameOrder::fixed);
    const auto fixed_b = meansWithVfcLeavingWork({"vfc", "statistical", "chc"}, FrameOrder::fixed);
    EXPECT_NEAR(fixed_a.at("chc") - fixed_b.at("chc"), 50.0, 1e-9);
    EXPECT_NEAR(fixed_b.at("statistical") - fixed_a.at("statistical"), 50.0, 1e-9);
}

// The world is shared by every configuration of a run: advanced (movers stepped, tree refit)
// once per frame, whatever the number of configurations, and once more per repetition.
TEST(Simulation, ConfigurationsOfOneBenchShareOneWorldSteppedOncePerFrame) {
    for (const std::vector<std::string>& algorithms :
         {std::vector<std::string>{"vfc"},
          std::vector<std::string>{"vfc", "statistical", "chc", "chc++", "async"}}) {
        BenchOptions options;
        options.algorithms = traitsOf(algorithms);
        options.frames = 7;
        options.repetitions = 2;
        const BenchResult r = runBenchmark(parseScenarioFile(kSmall), options);
        EXPECT_EQ(r.costs.world_advances, 14u) << algorithms.size() << " configurations";
        EXPECT_EQ(r.costs.world_steps, 12u) << "frame 0 of each repetition shows the initial state";
        EXPECT_GE(r.costs.world_update_ms_total, 0.0);
        // Every configuration saw the same world: the same movers and node changes each frame.
        for (const RunRecord& run : r.runs) {
            for (size_t f = 0; f < run.frames.size(); ++f) {
                EXPECT_EQ(run.frames[f].moved_objects, r.runs[0].frames[f].moved_objects);
                EXPECT_EQ(run.frames[f].node_changes, r.runs[0].frames[f].node_changes);
            }
        }
    }
}

// Sharing the world changes no decision: in deterministic-latency mode each configuration of a
// bench draws and queries exactly what it does when it runs alone (conditional in a GL context of
// its own, sim/run/config_contexts.h, the others in the run's).
TEST(Simulation, EveryConfigurationDecidesAsItDoesAlone) {
    const std::vector<std::string> names = {"stop-and-wait", "statistical", "statistical+",
                                            "chc",           "chc++",       "async",
                                            "conditional",   "ideal"};
    using Counts = std::vector<std::tuple<uint64_t, uint64_t, uint64_t>>;
    auto countsOf = [](const RunRecord& run) {
        Counts out;
        for (const FrameStats& f : run.frames)
            out.emplace_back(f.queries, f.objects_drawn, f.triangles);
        return out;
    };
    BenchOptions options;
    options.algorithms = traitsOf(names);
    options.latency = LatencyMode{true, 6};
    options.frames = 12;
    const BenchResult together = runBenchmark(parseScenarioFile(kSmall), options);
    ASSERT_EQ(together.runs.size(), names.size());
    EXPECT_EQ(together.metadata.contexts_apart, std::vector<std::string>{"conditional"});
    for (size_t c = 0; c < names.size(); ++c) {
        options.algorithms = traitsOf({names[c]});
        const BenchResult alone = runBenchmark(parseScenarioFile(kSmall), options);
        EXPECT_EQ(countsOf(together.runs[c]), countsOf(alone.runs[0])) << names[c];
    }
}

// Without --error and without an oracle no ground truth is rendered and no object-ID buffer is
// read back; with --error one render per frame serves every configuration.
TEST(Simulation, GroundTruthIsRenderedOnlyWhenSomethingNeedsIt) {
    BenchOptions options;
    options.algorithms = traitsOf({"vfc", "chc", "statistical"});
    options.frames = 5;
    const BenchResult plain = runBenchmark(parseScenarioFile(kSmall), options);
    EXPECT_EQ(plain.costs.ground_truth_renders, 0u);
    EXPECT_EQ(plain.costs.ground_truth_ms_total, 0.0);
    EXPECT_EQ(plain.costs.error_read_backs, 0u);
    EXPECT_EQ(plain.runs[0].frames[0].error_pixels, -1);

    options.measure_error = true;
    const BenchResult measured = runBenchmark(parseScenarioFile(kSmall), options);
    EXPECT_EQ(measured.costs.ground_truth_renders, 5u);
    EXPECT_EQ(measured.costs.error_read_backs, 15u);

    options.measure_error = false;
    options.algorithms = traitsOf({"vfc", "ideal"});  // the oracle needs ground truth, not error
    const BenchResult oracle = runBenchmark(parseScenarioFile(kSmall), options);
    EXPECT_EQ(oracle.costs.ground_truth_renders, 5u);
    EXPECT_EQ(oracle.costs.error_read_backs, 0u);
}

// runBenchmark() measures and returns; the files are written by the output layer afterwards
// (and the pictures by its frame hook), so a tool that only wants figures writes nothing.
TEST(Simulation, RunBenchmarkWritesNoFile) {
    auto entries = [] {
        std::set<std::filesystem::path> out;
        for (const auto& e : std::filesystem::directory_iterator(std::filesystem::current_path())) {
            out.insert(e.path());
        }
        return out;
    };
    const auto before = entries();
    BenchOptions options;
    options.algorithms = traitsOf({"vfc", "chc"});
    options.measure_error = true;
    options.frames = 3;
    const BenchResult result = runBenchmark(parseScenarioFile(kSmall), options);
    EXPECT_EQ(entries(), before);
    EXPECT_EQ(result.metadata.command, "bench");
    EXPECT_EQ(result.metadata.frames, 3u);
    EXPECT_EQ(result.metadata.objects, 300u);
    EXPECT_FALSE(result.metadata.renderer.empty());
}

// A scenario with a shadow-casting light renders its shadow pass, culled by the light's box alone,
// and with stereo two eyes culled by one frustum around both: the run says both once, so that
// nobody reads its figures as a frame of one view. Without them, no note.
TEST(Simulation, WhatARunRendersOfLightsAndStereoIsSaidOnce) {
    std::vector<std::string> notes;
    std::set<std::string> shown;
    BenchOptions options;
    options.algorithms = traitsOf({"vfc"});
    options.frames = 2;
    options.on_note = [&](const std::string& line) { notes.push_back(line); };
    options.warnings_shown = &shown;
    Scenario scenario = parseScenarioFile(kSmall);
    const BenchResult plain = runBenchmark(scenario, options);
    EXPECT_TRUE(notes.empty());
    scenario.lights.push_back(LightSpec{});
    scenario.stereo = StereoSpec{};
    const BenchResult lit = runBenchmark(scenario, options);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("teapots-small.json: light 0 renders a shadow pass drawing every "
                            "object in its box"),
              std::string::npos)
        << notes[0];
    EXPECT_NE(notes[0].find("stereo renders two eyes of 200x150 each, one above the other, "
                            "culled by one pass over a frustum enclosing both"),
              std::string::npos)
        << notes[0];
    // The frustum around both eyes holds the camera's: vfc draws no fewer.
    EXPECT_GE(lit.runs[0].summary.objects_mean, plain.runs[0].summary.objects_mean);
    runBenchmark(scenario, options);
    EXPECT_EQ(notes.size(), 1u) << "once a session";
}

}  // namespace
}  // namespace occsim
