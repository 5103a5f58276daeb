// Ground truth (sim/run/ground_truth.h): a fragment no point of its object can have (a stray
// fragment, sim/run/stray_fragments.h) is marked, is no error of a conservative culler, and is
// never marked on ordinary frames under either depth convention.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "error_bench.h"

namespace occsim {
namespace {

using testing::errorBench;
using testing::expectNoErrorAndNoMiss;
using testing::kScenarios;
using testing::summaryOf;

// llvmpipe draws one pixel of teapot 439 at 3.7 m on frame 9 of this scene while every vertex of
// it lies 7.2 to 9.2 m away (a depth extrapolated on a sliver triangle): CHC's query on the
// teapot's node rightly finds the box hidden, and that pixel used to count as CHC's error.
TEST(ErrorMetric, AStrayFragmentOfGroundTruthIsNoErrorOfAConservativeCuller) {
    const std::filesystem::path file =
        std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/general/dense-movers-near.json";
    const BenchResult result = errorBench(file, {"chc"}, 10);
    expectNoErrorAndNoMiss(result);
    int64_t stray = 0;
    for (const FrameStats& f : result.runs.at(0).frames) stray += f.stray_pixels;
    // The case is still there (if a Mesa update removes it, this test no longer proves anything).
    EXPECT_GT(stray, 0);
    EXPECT_EQ(summaryOf(result, "chc").stray_pixels_total, stray);
}

// The bound is never tighter than the geometry: on ordinary frames, under both depth
// conventions, ground truth marks no fragment stray.
class GroundTruthStray : public ::testing::TestWithParam<bool> {};

TEST_P(GroundTruthStray, NoFragmentOfTheSmallScenariosIsStray) {
    for (const char* name :
         {"teapots-small.json", "deep-depth-small.json", "city-small.json", "plant-small.json"}) {
        Scenario scenario = parseScenarioFile(kScenarios / name);
        scenario.conventional_depth = GetParam();
        const auto context = createHeadlessContext({}, scenario.width, scenario.height);
        const Scene scene = buildScene(scenario);
        GlRenderer renderer(scenario.width, scenario.height, depthConventionOf(scenario));
        uploadScene(scene, renderer);
        SharedWorld world(scene, scenario);
        GroundTruth truth(renderer);
        for (uint32_t f = 0; f < 12; ++f) {
            world.advance();
            const GroundTruthFrame& frame = truth.of(world);
            EXPECT_EQ(frame.stray_fragments, 0) << name << " frame " << f;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Depth, GroundTruthStray, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& param) {
                             return std::string(param.param ? "Conventional24" : "ReverseFloat");
                         });

}  // namespace
}  // namespace occsim
