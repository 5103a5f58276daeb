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
        options.algorithms.push_back(findAlgorithm(algo));
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

}  // namespace
}  // namespace occsim
