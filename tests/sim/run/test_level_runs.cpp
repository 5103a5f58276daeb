// The game levels end to end (scenarios/levels/, issue 42): the whole walk of each level, every
// 20th frame of it (the same camera, movers and animation times, 15 frames), in deterministic
// latency with the conservative query cullers and the Ideal oracle: zero error pixels and zero
// missed objects, and occlusion that matters (Ideal draws far fewer objects than frustum culling).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "occsim/culling/registry/registry.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

void expectConservativeAndOccluded(const std::string& name) {
    Scenario scenario =
        parseScenarioFile(fs::path(OCCSIM_SOURCE_DIR) / "scenarios/levels" / (name + ".json"));
    // Every 20th frame: the run's length and every moment in it (segments are in seconds), in
    // few frames. Big steps are what coherence likes least; conservative cullers must not care.
    scenario.dt_s *= 20;
    scenario.frames /= 20;
    scenario.warmup_frames = 0;
    BenchOptions options;
    for (const char* algo : {"vfc", "chc", "statistical", "statistical+", "ideal"}) {
        options.algorithms.push_back(findCuller(algo));
    }
    options.measure_error = true;
    options.latency = {true, 4};
    const BenchResult result = runBenchmark(scenario, options);
    ASSERT_EQ(result.runs.size(), 5u);
    for (const RunRecord& r : result.runs) {
        ASSERT_TRUE(r.algorithm->conservative) << r.algorithm->name;
        EXPECT_EQ(r.summary.error_pixels_total, 0) << name << ": " << r.algorithm->name;
        EXPECT_EQ(r.summary.missed_objects_total, 0) << name << ": " << r.algorithm->name;
    }
    const double vfc = result.runs[0].summary.objects_mean;
    const double ideal = result.runs[4].summary.objects_mean;
    EXPECT_LT(ideal, 0.5 * vfc) << name << ": Ideal draws " << ideal << " objects a frame, VFC "
                                << vfc;
}

TEST(LevelRuns, CourtyardsKeepZeroErrorWithOcclusionThatMatters) {
    expectConservativeAndOccluded("courtyards");
}

TEST(LevelRuns, InteriorKeepsZeroErrorWithOcclusionThatMatters) {
    expectConservativeAndOccluded("interior");
}

TEST(LevelRuns, CanyonKeepsZeroErrorWithOcclusionThatMatters) {
    expectConservativeAndOccluded("canyon");
}

// statistical+ on the canyon's main street (its first 60 frames, as recorded): props on the
// pavements hidden by the buildings beside them. The tree's cells are loose, so in its depth-first
// order some props come before the buildings that hide them; queried against a depth buffer
// without those buildings, they come back visible and are drawn for a whole re-query interval
// (when this test was written: 46,016 triangles a frame in the tree's order, 25,344 nearest
// first, ideal-box 24,191). Nearest first by distance, the buildings are drawn before the props
// are queried.
TEST(LevelRuns, StatisticalPlusQueriesCanyonPropsAfterTheBuildingsThatHideThem) {
    Scenario scenario =
        parseScenarioFile(fs::path(OCCSIM_SOURCE_DIR) / "scenarios/levels/canyon.json");
    BenchOptions options;
    options.algorithms = {findCuller("statistical+"), findCuller("ideal-box")};
    options.sweep = Sweep{"statistical+", "distance_order", {1.0, 0.0}};
    options.frames = 60;
    options.measure_error = true;
    options.latency = {true, 8};
    const BenchResult result = runBenchmark(scenario, options);
    ASSERT_EQ(result.runs.size(), 3u);
    const RunSummary& by_distance = result.runs[0].summary;
    const RunSummary& by_tree = result.runs[1].summary;
    const RunSummary& ideal_box = result.runs[2].summary;
    ASSERT_EQ(result.runs[2].algorithm->name, "ideal-box");
    for (const RunSummary* s : {&by_distance, &by_tree}) {
        EXPECT_EQ(s->error_pixels_total, 0);
        EXPECT_EQ(s->missed_objects_total, 0);
    }
    EXPECT_LT(by_distance.triangles_mean, 1.3 * ideal_box.triangles_mean)
        << "nearest first: " << by_distance.triangles_mean << " triangles a frame, ideal-box "
        << ideal_box.triangles_mean;
    EXPECT_LT(2.0 * by_distance.overdrawn_triangles_mean, by_tree.overdrawn_triangles_mean)
        << "over-drawn triangles a frame, nearest first " << by_distance.overdrawn_triangles_mean
        << ", in the tree's order " << by_tree.overdrawn_triangles_mean;
}

}  // namespace
}  // namespace occsim
