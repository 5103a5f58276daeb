// Where each configuration renders (sim/run/config_contexts.h): a culler that needs conditional
// rendering gets a GL context and renderer of its own, which draw what the run's draw, and the
// run's context is current again after each use and after they are gone.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "occsim/culling/contract/render_device.h"
#include "occsim/culling/registry/registry.h"
#include "render/headless_context.h"
#include "sim/run/config_contexts.h"
#include "sim/run/ground_truth.h"
#include "sim/run/run_config.h"
#include "sim/run/simulation.h"
#include "small_bench.h"

namespace occsim {
namespace {

using testing::kSmall;
using testing::traitsOf;

TEST(ConfigContexts, OnlyACullerThatNeedsConditionalRenderingRendersApart) {
    size_t apart = 0;
    for (const std::string& name : cullerNames()) {
        const CullerRow& row = *findCuller(name);
        EXPECT_EQ(rendersApart(row), (row.device_needs & kConditionalRendering) != 0) << name;
        apart += rendersApart(row) ? 1 : 0;
    }
    EXPECT_TRUE(rendersApart(*findCuller("conditional")));
    EXPECT_FALSE(rendersApart(*findCuller("vfc")));
    EXPECT_EQ(apart, 1u);  // conditional only, among the built-ins
}

// What a run has before its configurations: the small scenario's context, scene and renderer with
// the scene uploaded.
struct RunGl {
    Scenario scenario = parseScenarioFile(kSmall);
    std::unique_ptr<HeadlessContext> context =
        createHeadlessContext({}, scenario.width, scenario.height);
    Scene scene = buildScene(scenario);
    GlRenderer renderer{scenario.width, scenario.height, depthConventionOf(scenario)};

    RunGl() { uploadScene(scene, renderer); }
};

// The object IDs of the world's frame as ground truth draws them with `renderer` (its context
// current).
std::vector<uint32_t> idsDrawnBy(GlRenderer& renderer, const SharedWorld& world) {
    GroundTruth truth(renderer);
    return truth.of(world).ids;
}

TEST(ConfigContexts, AConfigurationApartDrawsWhatTheRunsContextDrawsAndLeavesItCurrent) {
    RunGl gl;
    SharedWorld world(gl.scene, gl.scenario);
    for (int f = 0; f < 5; ++f) world.advance();
    const std::vector<uint32_t> before = idsDrawnBy(gl.renderer, world);
    ASSERT_FALSE(before.empty());

    const std::vector<RunConfig> configs =
        planConfigs(traitsOf({"vfc", "conditional", "chc"}), gl.scenario.culler, std::nullopt);
    std::optional<std::vector<uint32_t>> apart_ids;
    {
        ConfigContexts contexts(configs, *gl.context, gl.renderer, gl.scene,
                                depthConventionOf(gl.scenario));
        EXPECT_FALSE(contexts.apart(0));
        EXPECT_TRUE(contexts.apart(1));
        EXPECT_FALSE(contexts.apart(2));
        EXPECT_EQ(&contexts.renderer(0), &gl.renderer);
        EXPECT_EQ(&contexts.renderer(2), &gl.renderer);
        EXPECT_NE(&contexts.renderer(1), &gl.renderer);
        EXPECT_EQ(contexts.apartLabels(configs), std::vector<std::string>{"conditional"});
        // The run's context is current after the constructor: its renderer still draws the frame.
        EXPECT_EQ(idsDrawnBy(gl.renderer, world), before);
        {
            const ConfigContexts::Use use(contexts, 1);
            apart_ids = idsDrawnBy(contexts.renderer(1), world);
        }
        EXPECT_EQ(idsDrawnBy(gl.renderer, world), before);
        {
            const ConfigContexts::Use use(contexts, 0);  // the run's own: nothing switches
            EXPECT_EQ(idsDrawnBy(contexts.renderer(0), world), before);
        }
    }
    ASSERT_TRUE(apart_ids.has_value());
    EXPECT_EQ(*apart_ids, before);
    // Destroying the context apart left the run's current and its objects whole.
    EXPECT_EQ(idsDrawnBy(gl.renderer, world), before);
}

TEST(ConfigContexts, ARunWithoutConditionalRenderingMakesNoContext) {
    RunGl gl;
    const std::vector<RunConfig> configs =
        planConfigs(traitsOf({"vfc", "hzb", "masked"}), gl.scenario.culler, std::nullopt);
    ConfigContexts contexts(configs, *gl.context, gl.renderer, gl.scene,
                            depthConventionOf(gl.scenario));
    for (size_t c = 0; c < configs.size(); ++c) {
        EXPECT_FALSE(contexts.apart(c));
        EXPECT_EQ(&contexts.renderer(c), &gl.renderer);
    }
    EXPECT_TRUE(contexts.apartLabels(configs).empty());
}

}  // namespace
}  // namespace occsim
