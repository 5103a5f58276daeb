// A configuration's culler made the one way runs, the tuner and the viewer make it
// (sim/run/culler_setup.h): a culler that weighs costs gets a cost model measured on this
// renderer, or the reference one when decisions must be reproducible; the others are left alone;
// a cost model the scenario gives is kept, and one given for a culler alone goes to it only.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <vector>

#include "culling/cullers/statistical_culler.h"
#include "occsim/culling/registry/registry.h"
#include "render/headless_context.h"
#include "sim/run/calibration.h"
#include "sim/run/culler_setup.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

namespace occsim {
namespace {

// The small teapot scenario built and uploaded on the default backend.
class CullerSetup : public ::testing::Test {
  protected:
    void SetUp() override {
        scenario_ = parseScenarioFile(std::filesystem::path(OCCSIM_SOURCE_DIR) /
                                      "scenarios/small/teapots-small.json");
        context_ = createHeadlessContext({}, scenario_.width, scenario_.height);
        scene_ = std::make_unique<Scene>(buildScene(scenario_));
        renderer_ = std::make_unique<GlRenderer>(scenario_.width, scenario_.height);
        uploadScene(*scene_, *renderer_);
    }

    Scenario scenario_;
    std::unique_ptr<HeadlessContext> context_;
    std::unique_ptr<Scene> scene_;
    std::unique_ptr<GlRenderer> renderer_;
};

TEST_F(CullerSetup, ReproducibleDecisionsTakeTheReferenceCostModel) {
    std::vector<RunConfig> configs{
        RunConfig{"statistical+", findCuller("statistical+"), scenario_.culler}};
    const auto choice =
        chooseCostModel(configs, *scene_, scenario_, *renderer_, LatencyMode{true, 8});
    ASSERT_TRUE(choice);
    EXPECT_EQ(choice->source, CostModelSource::Reference);
    EXPECT_EQ(configs[0].culler.cost_model, referenceCostModel());
}

TEST_F(CullerSetup, ACostModelGivenForOneCullerGoesToThatCullerOnly) {
    Scenario given = scenario_;
    given.culler.cost_model_of["statistical+"] = CostModel{0.25, 0.002, 0.0};
    // The paper's culler weighs no costs unless told to.
    given.culler.edit(*findCuller("statistical")).set("cost_model", 1.0);
    std::vector<RunConfig> configs{
        RunConfig{"statistical+", findCuller("statistical+"), given.culler},
        RunConfig{"statistical", findCuller("statistical"), given.culler}};
    const auto choice = chooseCostModel(configs, *scene_, given, *renderer_, LatencyMode{true, 8});
    ASSERT_TRUE(choice);
    EXPECT_EQ(configs[0].culler.cost_model, (CostModel{0.25, 0.002, 0.0}));
    EXPECT_EQ(configs[1].culler.cost_model, referenceCostModel())
        << "statistical was given none of its own";
}

TEST_F(CullerSetup, NoConfigurationThatWeighsCostsIsNoChoice) {
    std::vector<RunConfig> configs{RunConfig{"vfc", findCuller("vfc"), scenario_.culler},
                                   RunConfig{"chc", findCuller("chc"), scenario_.culler}};
    EXPECT_FALSE(chooseCostModel(configs, *scene_, scenario_, *renderer_, LatencyMode{}));
    EXPECT_FALSE(configs[0].culler.cost_model.known());
    EXPECT_FALSE(configs[1].culler.cost_model.known());
}

// The viewer makes its cullers through this one construction path, as runs do: a culler that
// weighs costs gets a cost model measured on this renderer, the others are left alone, and a cost
// model the scenario gives is kept.
TEST_F(CullerSetup, CullersAreMadeAsRunsMakeThemWithTheCostModelStep) {
    std::vector<RunConfig> configs{
        RunConfig{"vfc", findCuller("vfc"), scenario_.culler},
        RunConfig{"statistical+", findCuller("statistical+"), scenario_.culler}};
    const auto choice = chooseCostModel(configs, *scene_, scenario_, *renderer_, LatencyMode{});
    ASSERT_TRUE(choice);
    EXPECT_EQ(choice->source, CostModelSource::Calibrated);
    EXPECT_FALSE(configs[0].culler.cost_model.known()) << "vfc weighs no costs";
    ASSERT_TRUE(configs[1].culler.cost_model.known());
    const std::unique_ptr<Culler> culler = makeConfiguredCuller(configs[1]);
    const auto* statistical = dynamic_cast<const StatisticalCuller*>(culler.get());
    ASSERT_NE(statistical, nullptr);
    EXPECT_EQ(statistical->costModel(), configs[1].culler.cost_model);

    Scenario given = scenario_;
    given.culler.cost_model = CostModel{0.5, 0.001, 0.0};
    std::vector<RunConfig> kept{
        RunConfig{"statistical+", findCuller("statistical+"), given.culler}};
    EXPECT_EQ(chooseCostModel(kept, *scene_, given, *renderer_, LatencyMode{})->source,
              CostModelSource::Scenario);
    EXPECT_EQ(kept[0].culler.cost_model, (CostModel{0.5, 0.001, 0.0}));
}

}  // namespace
}  // namespace occsim
