// The scenario's expectations: an object, parsed with the scenario.
#include <gtest/gtest.h>

#include "scenario_fixtures.h"

namespace occsim {
namespace {

using namespace fixtures;

TEST(ScenarioTypes, ExpectMustBeAnObject) {
    json scenario = minimalScenario();
    scenario["expect"] = json::array();
    expectError(scenario, "/expect", "expected an object");
}
// The expect block is read with the rest of the scenario: a mistake in it is a parse error.
TEST(ScenarioExpect, IsParsedWithTheScenario) {
    json scenario = minimalScenario();
    scenario["expect"] = {{"anything", {1, 2, 3}}};
    expectError(scenario, "/expect/anything", "unknown key 'anything'");
    scenario["expect"] = {{"algorithms", {"vfc", "nope"}}};
    expectError(scenario, "/expect/algorithms/1", "expected one of");
}

}  // namespace
}  // namespace occsim
