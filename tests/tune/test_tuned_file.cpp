// tuned.json: read back through the scenario readers, the cost model written only when it fits
// well and asked for, the setting written for each verdict.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "sim/scenario/culling_file.h"
#include "tune/tuned_file.h"
#include "tune_fixtures.h"

namespace occsim::tune {
namespace {

using namespace fixtures;

TEST(TunedFile, ReadsBackThroughTheScenarioReadersAsTheTunedValues) {
    OptionValues tuned(statistical().options);
    tuned.set("base_time", 0.123456789012345);
    tuned.set("decay_a", 2.75);
    const TunedFile file = tunedFile(statistical(), Setting{"tuned", tuned, std::nullopt});
    const nlohmann::json json = nlohmann::json::parse(file.text);
    Scenario s;
    s.algorithm = "vfc";
    applyCullingFile(CullingFile{"tuned.json", json}, s);
    EXPECT_EQ(s.algorithm, "statistical");
    EXPECT_EQ(s.culler.of(statistical()).number("base_time"), 0.123456789012345);
    EXPECT_EQ(s.culler.of(statistical()).number("decay_a"), 2.75);
    EXPECT_FALSE(file.has_cost_option);
    EXPECT_FALSE(s.culler.cost_model.known());

    // A setting with a cost model: the file carries it for statistical+ alone, read back as that
    // culler's cost model; the shared one, which other cullers read, stays unknown.
    const CullerRow& plus = *findCuller("statistical+");
    const std::optional<CostModel> model = costModelOf(FrameTimeModel{1.0, 0.02, 0.1, 0.01, 1.0});
    ASSERT_TRUE(model);
    const TunedFile plus_file =
        tunedFile(plus, Setting{"tuned", OptionValues(plus.options), model});
    Scenario p;
    applyCullingFile(CullingFile{"tuned.json", nlohmann::json::parse(plus_file.text)}, p);
    EXPECT_TRUE(plus_file.has_cost_option);
    EXPECT_NE(plus_file.note.find("for statistical+ only"), std::string::npos) << plus_file.note;
    EXPECT_FALSE(p.culler.cost_model.known()) << "no other culler gets the fitted cost model";
    ASSERT_EQ(p.culler.cost_model_of.count("statistical+"), 1u);
    const occsim::CostModel& scoped = p.culler.cost_model_of.at("statistical+");
    EXPECT_DOUBLE_EQ(scoped.query_box_ms, 0.02);
    EXPECT_DOUBLE_EQ(scoped.triangle_ms, 0.1 / 1000.0);
    EXPECT_DOUBLE_EQ(scoped.draw_call_ms, 0.01);
    EXPECT_FALSE(costModelOf(FrameTimeModel{1.0, 0.0, 0.0, 0.0, 1.0}));
}

// A fitted model with these figures, converged, explaining frames of `mean_ms` with a residual
// RMS of `residual_ms`.
FrameTimeModelFit fittedCosts(double mean_ms, double residual_ms) {
    FrameTimeModelFit f;
    f.model = FrameTimeModel{1.0, 0.02, 0.1, 0.01, 1.0};
    f.fit.converged = true;
    f.mean_frame_ms = mean_ms;
    f.residual_rms_ms = residual_ms;
    return f;
}

// The cost model goes into the confirmed (and written) setting only for a culler that weighs
// costs and only when it fits well enough: a residual RMS at most 25 % of the mean frame. The
// issue's session had 123 %: its file carried a model that changed every decision.
TEST(TunedFile, TheCostModelIsConfirmedAndWrittenOnlyWhenItFitsWell) {
    const CullerRow& plus = *findCuller("statistical+");
    const OptionValues options(plus.options);
    std::string why;
    const Setting poor = tunedSetting(plus, options, fittedCosts(10.0, 12.3), true, &why);
    EXPECT_FALSE(poor.cost_model) << "a residual of 123 % of the mean frame steers by noise";
    EXPECT_NE(why.find("residual RMS 123 % of the mean frame, above the 25 % allowed"),
              std::string::npos)
        << why;
    EXPECT_FALSE(tunedFile(plus, poor).has_cost_option);

    const Setting good = tunedSetting(plus, options, fittedCosts(10.0, 2.5), true, &why);
    ASSERT_TRUE(good.cost_model) << why;
    EXPECT_TRUE(why.empty()) << why;
    EXPECT_DOUBLE_EQ(good.cost_model->query_box_ms, 0.02);
    EXPECT_FALSE(good.sameSettingAs(Setting{"paper", options, std::nullopt}))
        << "the same options with a cost model are another setting";

    FrameTimeModelFit zero = fittedCosts(10.0, 1.0);
    zero.model = FrameTimeModel{1.0, 0.0, 0.0, 0.0, 1.0};
    EXPECT_FALSE(tunedSetting(plus, options, zero, true, &why).cost_model);
    EXPECT_NE(why.find("cost_model.json only"), std::string::npos) << why;
    FrameTimeModelFit unconverged = fittedCosts(10.0, 1.0);
    unconverged.fit.converged = false;
    EXPECT_FALSE(tunedSetting(plus, options, unconverged, true, &why).cost_model);

    // The paper's culler weighs no costs: never a cost model, and nothing to explain.
    EXPECT_FALSE(tunedSetting(statistical(), OptionValues(statistical().options),
                              fittedCosts(10.0, 1.0), true, &why)
                     .cost_model);
    EXPECT_TRUE(why.empty()) << why;
}

// Unless asked for (occtune --apply-cost-model), even a model that fits well stays out of the
// confirmed setting: the samples ran with the culler's start-up calibration, and the
// confirmation measures what they measured. The line says so and how to ask for it.
TEST(TunedFile, AWellFittingCostModelIsAppliedOnlyWhenAskedFor) {
    const CullerRow& plus = *findCuller("statistical+");
    const OptionValues options(plus.options);
    std::string why;
    const Setting unasked = tunedSetting(plus, options, fittedCosts(10.0, 1.0), false, &why);
    EXPECT_FALSE(unasked.cost_model);
    EXPECT_NE(why.find("calibrates at start-up, as in every sample"), std::string::npos) << why;
    EXPECT_NE(why.find("--apply-cost-model"), std::string::npos) << why;
    EXPECT_TRUE(unasked.sameSettingAs(Setting{"paper", options, std::nullopt}));
    EXPECT_FALSE(tunedFile(plus, unasked).has_cost_option);
    EXPECT_TRUE(tunedSetting(plus, options, fittedCosts(10.0, 1.0), true, &why).cost_model);
}

// "no change" writes the reference setting (no cost model), so that the file changes no
// decision; the other verdicts write what was confirmed.
TEST(TunedFile, NoChangeWritesTheReferenceSettingAndTheOthersTheConfirmedOne) {
    const CullerRow& plus = *findCuller("statistical+");
    const Setting reference{"paper", OptionValues(plus.options), std::nullopt};
    std::string why;
    const Setting tuned =
        tunedSetting(plus, OptionValues(plus.options), fittedCosts(10.0, 1.0), true, &why);
    ASSERT_TRUE(tuned.cost_model);
    const Verdict no_change{Verdict::Kind::NoChange, "same decisions"};
    EXPECT_EQ(&writtenSetting(no_change, tuned, reference), &reference);
    EXPECT_FALSE(tunedFile(plus, writtenSetting(no_change, tuned, reference)).has_cost_option);
    const Verdict accepted{Verdict::Kind::Accepted, "faster"};
    EXPECT_EQ(&writtenSetting(accepted, tuned, reference), &tuned);
    EXPECT_TRUE(tunedFile(plus, writtenSetting(accepted, tuned, reference)).has_cost_option);
}

}  // namespace
}  // namespace occsim::tune
