// The scenario's culling section: every culler's options read, each out of its range refused at its
// key with the descriptor's range, and an unknown culler named with the valid names.
#include <gtest/gtest.h>

#include <string>

#include "scenario_fixtures.h"

namespace occsim {
namespace {

using namespace fixtures;

TEST(ScenarioRanges, InvalidStatisticalOptionsReportTheDescriptorsRangeAtTheirKey) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"statistical", {{"decay_b", 1.5}}}};
    expectError(scenario, "/culling/statistical/decay_b", "expected a number in [0, 1], got 1.5");
}

TEST(ScenarioCulling, StatisticalPlusHasItsOwnOptionsWithEveryImprovementOn) {
    json scenario = minimalScenario();
    const Scenario plain = parseScenarioText(scenario.dump(), "x.json");
    EXPECT_FALSE(statisticalOf(plain).ready_answers) << "the paper by default";
    EXPECT_FALSE(statisticalOf(plain).cost_model);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").ready_answers);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").virtual_leaves);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").object_queries);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").cost_model);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").fallback);
    EXPECT_GT(statisticalOf(plain, "statistical+").requery_parallax, 0.0);
    EXPECT_FALSE(plain.culler.cost_model.known()) << "measured at start-up unless given";

    scenario["culling"] = {
        {"algorithm", "statistical+"},
        {"statistical+",
         {{"fallback", false},
          {"requery_distance", 4.0},
          {"requery_parallax", 0},
          {"base_time", 0.5}}},
        {"statistical", {{"virtual_leaves", true}, {"object_queries", true}}},
        {"cost_model", {{"query_box_ms", 0.02}, {"triangle_ms", 6e-5}, {"draw_call_ms", 0.001}}}};
    const Scenario s = parseScenarioText(scenario.dump(), "x.json");
    EXPECT_EQ(s.algorithm, "statistical+");
    EXPECT_FALSE(statisticalOf(s, "statistical+").fallback);
    EXPECT_TRUE(statisticalOf(s, "statistical+").ready_answers)
        << "keys not given keep the plus defaults";
    EXPECT_DOUBLE_EQ(statisticalOf(s, "statistical+").requery_distance_m, 4.0);
    EXPECT_DOUBLE_EQ(statisticalOf(s, "statistical+").base_time_s, 0.5);
    EXPECT_TRUE(statisticalOf(s).virtual_leaves);
    EXPECT_TRUE(statisticalOf(s).object_queries);
    EXPECT_FALSE(statisticalOf(s).ready_answers);
    EXPECT_EQ(s.culler.cost_model, (CostModel{0.02, 6e-5, 0.001}));
}

TEST(ScenarioRanges, InvalidStatisticalPlusAndCostModelReportTheirObjects) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"statistical+", {{"requery_distance", 3.0}}}};
    expectError(scenario, "/culling/statistical+",
                "requery_distance and requery_parallax are alternatives");
    scenario["culling"] = {{"statistical+", {{"fallback_visible_share", 1.5}}}};
    expectError(scenario, "/culling/statistical+/fallback_visible_share",
                "expected a number in [0, 1], got 1.5");
    scenario["culling"] = {{"cost_model", {{"query_box_ms", -1.0}}}};
    expectError(scenario, "/culling/cost_model", "finite numbers >= 0");
    scenario["culling"] = {{"cost_model", {{"query_box_ms", 0.0}}}};
    expectError(scenario, "/culling/cost_model", "at least one figure > 0");
    scenario["culling"] = {{"cost_model", {{"query_ms", 0.1}}}};
    expectError(scenario, "/culling/cost_model/query_ms", "unknown key");
}

TEST(ScenarioRanges, InvalidPeerCullerOptionsReportTheDescriptorsRangeAtTheirKey) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"chc", {{"visible_frames_skip", 2000000}}}};
    expectError(scenario, "/culling/chc/visible_frames_skip",
                "expected an integer in [0, 1000000] (frames), got 2000000");
    scenario["culling"] = {{"chc++", {{"batch_size", 0}}}};
    expectError(scenario, "/culling/chc++/batch_size",
                "expected an integer in [1, 4294967295] (nodes), got 0");
    scenario["culling"] = {{"chc++", {{"tight_bounds_depth", 9}}}};
    expectError(scenario, "/culling/chc++/tight_bounds_depth",
                "expected an integer in [0, 6] (tree levels), got 9");
    scenario["culling"] = {{"chc++", {{"multiqueries", 1}}}};
    expectError(scenario, "/culling/chc++/multiqueries", "expected true or false");
    scenario["culling"] = {{"async", {{"retest_interval_frames", 0}}}};
    expectError(scenario, "/culling/async/retest_interval_frames",
                "expected an integer in [1, 1000000] (frames), got 0");
    scenario["culling"] = {{"async", {{"retest_interval", 3}}}};
    expectError(scenario, "/culling/async/retest_interval", "unknown key 'retest_interval'");
}

TEST(ScenarioCulling, PeerCullerOptionsAreRead) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"algorithm", "chc++"},
                           {"threshold_pixels", 25},
                           {"stale_results", true},
                           {"chc", {{"visible_frames_skip", 2}}},
                           {"chc++",
                            {{"visible_frames_skip", 7},
                             {"batch_size", 20},
                             {"multiqueries", false},
                             {"tight_bounds_depth", 2},
                             {"seed", 99}}},
                           {"async", {{"retest_interval_frames", 9}}}};
    const Scenario s = parseScenarioText(scenario.dump(), kFile);
    EXPECT_EQ(s.algorithm, "chc++");
    EXPECT_EQ(optionsOf(s, "chc").number("visible_frames_skip"), 2.0);
    EXPECT_EQ(s.culler.approximation.threshold_pixels, 25.0);
    EXPECT_TRUE(s.culler.approximation.stale_results);
    EXPECT_EQ(optionsOf(s, "chc++").number("visible_frames_skip"), 7.0);
    EXPECT_EQ(optionsOf(s, "chc++").number("batch_size"), 20.0);
    EXPECT_FALSE(optionsOf(s, "chc++").flag("multiqueries"));
    EXPECT_EQ(optionsOf(s, "chc++").number("tight_bounds_depth"), 2.0);
    EXPECT_EQ(optionsOf(s, "chc++").number("seed"), 99.0);
    EXPECT_EQ(optionsOf(s, "async").number("retest_interval_frames"), 9.0);
    const Scenario defaults = parseScenarioText(minimalScenario().dump(), kFile);
    EXPECT_EQ(optionsOf(defaults, "chc++").number("batch_size"), 50.0);
    EXPECT_EQ(optionsOf(defaults, "async").number("retest_interval_frames"), 5.0);
}

TEST(ScenarioRanges, InvalidBspOptionsReportIsValidMessage) {
    json scenario = minimalScenario();
    scenario["bsp"] = {{"max_depth", 65}};
    expectError(scenario, "/bsp", "max_depth must be in [0, 64]");
}
TEST(ScenarioEnums, UnknownAlgorithmListsValidNames) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"algorithm", "statstical"}};
    // Every registered culler, in the registry's order (the list is the registry's, not typed).
    std::string names;
    for (const std::string& n : cullerNames()) names += (names.empty() ? "\"" : ", \"") + n + "\"";
    EXPECT_NE(names.find("\"vfc\", \"stop-and-wait\", \"statistical\""), std::string::npos);
    expectError(scenario, "/culling/algorithm",
                "expected one of " + names + " (did you mean \"statistical\"?), got " +
                    "\"statstical\" (string)");
}

}  // namespace
}  // namespace occsim
