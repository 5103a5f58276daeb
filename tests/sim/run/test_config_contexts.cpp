// Where each configuration renders (sim/run/config_contexts.h): a culler that needs conditional
// rendering gets a GL context and renderer of its own, which draw what the run's draw, and the
// run's context is current again after each use and after they are gone.
#include <gtest/gtest.h>

#include <cstdint>
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

// The object IDs of the world's frame as ground truth draws them with `renderer` (its context
// current).
std::vector<uint32_t> idsDrawnBy(GlRenderer& renderer, const SharedWorld& world) {
    GroundTruth truth(renderer);
    return truth.of(world).ids;
}

TEST(ConfigContexts, AConfigurationApartDrawsWhatTheRunsContextDrawsAndLeavesItCurrent) {
    const Scenario scenario = parseScenarioFile(kSmall);
    const auto context = createHeadlessContext({}, scenario.width, scenario.height);
    const Scene scene = buildScene(scenario);
    GlRenderer renderer(scenario.width, scenario.height, depthConventionOf(scenario));
    uploadScene(scene, renderer);
    SharedWorld world(scene, scenario);
    for (int f = 0; f < 5; ++f) world.advance();
    const std::vector<uint32_t> before = idsDrawnBy(renderer, world);
    ASSERT_FALSE(before.empty());

    const std::vector<RunConfig> configs =
        planConfigs(traitsOf({"vfc", "conditional", "chc"}), scenario.culler, std::nullopt);
    std::optional<std::vector<uint32_t>> apart_ids;
    {
        ConfigContexts contexts(configs, *context, renderer, scene, depthConventionOf(scenario));
        EXPECT_FALSE(contexts.apart(0));
        EXPECT_TRUE(contexts.apart(1));
        EXPECT_FALSE(contexts.apart(2));
        EXPECT_EQ(&contexts.renderer(0), &renderer);
        EXPECT_EQ(&contexts.renderer(2), &renderer);
        EXPECT_NE(&contexts.renderer(1), &renderer);
        EXPECT_EQ(contexts.apartLabels(configs), std::vector<std::string>{"conditional"});
        // The run's context is current after the constructor: its renderer still draws the frame.
        EXPECT_EQ(idsDrawnBy(renderer, world), before);
        {
            const ConfigContexts::Use use(contexts, 1);
            apart_ids = idsDrawnBy(contexts.renderer(1), world);
        }
        EXPECT_EQ(idsDrawnBy(renderer, world), before);
        {
            const ConfigContexts::Use use(contexts, 0);  // the run's own: nothing switches
            EXPECT_EQ(idsDrawnBy(contexts.renderer(0), world), before);
        }
    }
    ASSERT_TRUE(apart_ids.has_value());
    EXPECT_EQ(*apart_ids, before);
    // Destroying the context apart left the run's current and its objects whole.
    EXPECT_EQ(idsDrawnBy(renderer, world), before);
}

TEST(ConfigContexts, ARunWithoutConditionalRenderingMakesNoContext) {
    const Scenario scenario = parseScenarioFile(kSmall);
    const auto context = createHeadlessContext({}, scenario.width, scenario.height);
    const Scene scene = buildScene(scenario);
    GlRenderer renderer(scenario.width, scenario.height, depthConventionOf(scenario));
    uploadScene(scene, renderer);
    const std::vector<RunConfig> configs =
        planConfigs(traitsOf({"vfc", "hzb", "masked"}), scenario.culler, std::nullopt);
    ConfigContexts contexts(configs, *context, renderer, scene, depthConventionOf(scenario));
    for (size_t c = 0; c < configs.size(); ++c) {
        EXPECT_FALSE(contexts.apart(c));
        EXPECT_EQ(&contexts.renderer(c), &renderer);
    }
    EXPECT_TRUE(contexts.apartLabels(configs).empty());
}

}  // namespace
}  // namespace occsim
