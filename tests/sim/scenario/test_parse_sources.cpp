// The scenario's sources and movers: each source's occluder role, each motion with its own keys
// and no other's, and indices that must name objects that exist.
#include <gtest/gtest.h>

#include "scenario_fixtures.h"

namespace occsim {
namespace {

using namespace fixtures;

TEST(ScenarioSources, OccludersSaysWhetherASourcesObjectsOccludeInMasked) {
    json scenario = minimalScenario();
    EXPECT_EQ(parseScenarioText(scenario.dump(), kFile).sources.at(0).occluders,
              OccluderRole::BySize);
    scenario["scene"]["sources"][0]["occluders"] = "never";
    EXPECT_EQ(parseScenarioText(scenario.dump(), kFile).sources.at(0).occluders,
              OccluderRole::Never);
    scenario["scene"]["sources"][0]["occluders"] = "always";
    EXPECT_EQ(parseScenarioText(scenario.dump(), kFile).sources.at(0).occluders,
              OccluderRole::Always);
    scenario["scene"]["sources"][0]["occluders"] = "sometimes";
    expectError(scenario, "/scene/sources/0/occluders",
                "expected one of \"by_size\", \"always\", \"never\"");
    scenario["scene"]["sources"][0]["occluders"] = true;
    expectError(scenario, "/scene/sources/0/occluders", "expected one of");
}
TEST(ScenarioEnums, UnknownSourceTypeListsValidTypes) {
    json scenario = minimalScenario();
    scenario["scene"]["sources"][0]["type"] = "terrain";
    expectError(scenario, "/scene/sources/0/type",
                "expected one of \"teapots\", \"gltf\", \"city\", \"library\", \"plant\"");
}

TEST(ScenarioMovers, OrbitWithRegionIsRejected) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.1},
                           {"motion", "orbit"},
                           {"region", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}}};
    expectError(scenario, "/movers/0/region", "'region' is not allowed with motion \"orbit\"");
}

TEST(ScenarioMovers, BounceWithRadiusIsRejected) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.1}, {"motion", "bounce"}, {"radius", {1, 2}}}};
    expectError(scenario, "/movers/0/radius", "'radius' is not allowed with motion \"bounce\"");
}

TEST(ScenarioMovers, NeedExactlyOneSelection) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"motion", "bounce"}}};
    expectError(scenario, "/movers/0", "expected exactly one of 'fraction', 'objects' or 'spawn'");
    scenario["movers"] = {{{"motion", "bounce"}, {"fraction", 0.1}, {"objects", {1}}}};
    expectError(scenario, "/movers/0", "got 2");
}

TEST(ScenarioMovers, EveryMotionTypeParsesWithItsOwnKeys) {
    json scenario = minimalScenario();
    scenario["movers"] = {
        {{"spawn", {{"count", 5}, {"shape", "box"}, {"size", {1, 2}}}},
         {"motion", "path"},
         {"waypoints", {{0, 0, 0}, {10, 0, 0}, {10, 0, 10}}},
         {"speed", {3, 5}}},
        {{"objects", {0}}, {"motion", "spin"}, {"spin", {10, 20}}},
        {{"fraction", 0.2}, {"motion", "random_walk"}, {"turn_rate", 45}, {"speed", {1, 1}}},
    };
    const Scenario s = parseScenarioText(scenario.dump(), kFile);
    ASSERT_EQ(s.movers.size(), 3u);
    EXPECT_EQ(s.movers[0].selection, MoverSelection::Spawn);
    EXPECT_EQ(s.movers[0].spawn.shape, SpawnShape::Box);
    EXPECT_EQ(s.movers[0].waypoints.size(), 3u);
    EXPECT_EQ(s.movers[1].motion, MotionType::Spin);
    EXPECT_DOUBLE_EQ(s.movers[1].spin_max_deg_s, 20.0);
    EXPECT_EQ(s.movers[2].motion, MotionType::RandomWalk);
    EXPECT_DOUBLE_EQ(s.movers[2].turn_rate_deg_s, 45.0);
}

TEST(ScenarioMovers, KeysOfAnotherMotionAreRejected) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.1}, {"motion", "spin"}, {"speed", {1, 2}}}};
    expectError(scenario, "/movers/0/speed", "'speed' is not allowed with motion \"spin\"");
    scenario["movers"] = {
        {{"fraction", 0.1}, {"motion", "bounce"}, {"waypoints", {{0, 0, 0}, {1, 0, 0}}}}};
    expectError(scenario, "/movers/0/waypoints", "applies to path only");
}

TEST(ScenarioMovers, SourceIndexMustExist) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.1}, {"motion", "bounce"}, {"source", 1}}};
    expectError(scenario, "/movers/0/source", "which has 1 entry, got 1");
}

TEST(ScenarioMovers, MotionIsRequired) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.5}}};
    expectError(scenario, "/movers/0/motion", "missing required key 'motion'");
}
// Mover object indices are checked by the parser where the source's spec tells its object count.
TEST(ScenarioMovers, ObjectIndicesPastATeapotFieldAreRejectedByTheParser) {
    json scenario = minimalScenario();
    scenario["scene"]["sources"][0] = {{"type", "teapots"}, {"count", 5}};
    scenario["movers"] = {{{"motion", "spin"}, {"objects", {0, 4, 5}}}};
    expectError(scenario, "/movers/0/objects/2", "expected an object index < 5");
}

}  // namespace
}  // namespace occsim
