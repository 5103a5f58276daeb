// The "lights" and "stereo" sections (sim/scenario/parse_views.cpp): defaults, every field read,
// and every bad value one error naming the file, the JSON pointer and what was expected.
#include <gtest/gtest.h>

#include "scenario_fixtures.h"

namespace occsim {
namespace {

using namespace fixtures;

Scenario parsed(const json& scenario) { return parseScenarioText(scenario.dump(), kFile); }

TEST(ScenarioViews, AScenarioWithoutThemHasNoLightsAndNoSecondEye) {
    const Scenario s = parsed(minimalScenario());
    EXPECT_TRUE(s.lights.empty());
    EXPECT_FALSE(s.stereo.has_value());
}

TEST(ScenarioViews, ADirectionalLightTakesItsDefaultsAndANormalisedDirection) {
    json scenario = minimalScenario();
    scenario["lights"] = {{{"type", "directional"}, {"direction", {0, -2, 0}}}};
    const Scenario s = parsed(scenario);
    ASSERT_EQ(s.lights.size(), 1u);
    const LightSpec& l = s.lights[0];
    EXPECT_EQ(l.type, LightType::Directional);
    EXPECT_EQ(l.direction, glm::dvec3(0, -1, 0));
    EXPECT_EQ(l.shadow_map, 2048u);
    EXPECT_TRUE(l.casts_shadows);
}

TEST(ScenarioViews, ASpotLightReadsItsPositionConeAndRange) {
    json scenario = minimalScenario();
    scenario["lights"] = {{{"type", "directional"}, {"direction", {1, -1, 0}}},
                          {{"type", "spot"},
                           {"direction", {0, 0, -3}},
                           {"position", {1, 5, 2}},
                           {"outer_cone", 30},
                           {"range", 40},
                           {"shadow_map", 512},
                           {"casts_shadows", false}}};
    const Scenario s = parsed(scenario);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_NEAR(s.lights[0].direction.x, std::sqrt(0.5), 1e-15);
    const LightSpec& spot = s.lights[1];
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_EQ(spot.direction, glm::dvec3(0, 0, -1));
    EXPECT_EQ(spot.position, glm::dvec3(1, 5, 2));
    EXPECT_EQ(spot.outer_cone_deg, 30.0);
    EXPECT_EQ(spot.range_m, 40.0);
    EXPECT_EQ(spot.shadow_map, 512u);
    EXPECT_FALSE(spot.casts_shadows);
}

TEST(ScenarioViews, BadLightsAreOneErrorNamingTheKey) {
    json scenario = minimalScenario();
    scenario["lights"] = {{{"type", "directional"}, {"direction", {0, 0, 0}}}};
    expectError(scenario, "/lights/0/direction", "expected a non-zero direction");
    scenario["lights"] = {{{"type", "directional"}, {"direction", {1e-320, 0, 0}}}};
    expectError(scenario, "/lights/0/direction", "expected a non-zero direction");
    scenario["lights"] = {{{"type", "directional"}}};
    expectError(scenario, "/lights/0/direction", "");
    scenario["lights"] = {{{"type", "point"}, {"direction", {0, -1, 0}}}};
    expectError(scenario, "/lights/0/type", "expected one of");
    scenario["lights"] = {{{"type", "directional"}, {"direction", {0, -1, 0}}, {"shadow_map", 0}}};
    expectError(scenario, "/lights/0/shadow_map", "");
    scenario["lights"] = {
        {{"type", "directional"}, {"direction", {0, -1, 0}}, {"shadow_map", 16385}}};
    expectError(scenario, "/lights/0/shadow_map", "16384");
    scenario["lights"] = {{{"type", "spot"}, {"direction", {0, -1, 0}}}};
    expectError(scenario, "/lights/0/position", "");
    scenario["lights"] = {
        {{"type", "spot"}, {"direction", {0, -1, 0}}, {"position", {0, 0, 0}}, {"outer_cone", 90}}};
    expectError(scenario, "/lights/0/outer_cone", "");
    scenario["lights"] = {{{"type", "directional"}, {"direction", {0, -1, 0}}, {"outer_cone", 30}}};
    expectError(scenario, "/lights/0/outer_cone", "unknown key");
    scenario["lights"] = json::object();
    expectError(scenario, "/lights", "expected an array");
}

TEST(ScenarioViews, StereoReadsItsSeparationAndCulling) {
    json scenario = minimalScenario();
    scenario["stereo"] = json::object();
    Scenario s = parsed(scenario);
    ASSERT_TRUE(s.stereo.has_value());
    EXPECT_EQ(s.stereo->eye_separation_m, 0.064);
    EXPECT_EQ(s.stereo->culling, StereoCulling::Enclosing);
    scenario["stereo"] = {{"eye_separation", 0.07}, {"culling", "per_eye"}};
    s = parsed(scenario);
    EXPECT_EQ(s.stereo->eye_separation_m, 0.07);
    EXPECT_EQ(s.stereo->culling, StereoCulling::PerEye);
}

TEST(ScenarioViews, BadStereoIsOneErrorNamingTheKey) {
    json scenario = minimalScenario();
    scenario["stereo"] = {{"eye_separation", -0.06}};
    expectError(scenario, "/stereo/eye_separation", "");
    scenario["stereo"] = {{"eye_separation", 0}};
    expectError(scenario, "/stereo/eye_separation", "");
    scenario["stereo"] = {{"culling", "both"}};
    expectError(scenario, "/stereo/culling", "expected one of");
    scenario["stereo"] = {{"eyes", 2}};
    expectError(scenario, "/stereo/eyes", "unknown key");
}

// A glTF source's "lights": its file's lights read with their shadows (the default), without, or
// left out; anything else is one error at the key.
TEST(ScenarioViews, AGltfSourceSaysWhatItsFilesLightsDo) {
    json scenario = minimalScenario();
    const std::string box = std::string(OCCSIM_SOURCE_DIR) + "/scenarios/assets/Box/box.gltf";
    scenario["scene"]["sources"] = {{{"type", "gltf"}, {"path", box}}};
    EXPECT_EQ(std::get<GltfSourceSpec>(parsed(scenario).sources[0].spec).lights,
              GltfLights::Shadows);
    scenario["scene"]["sources"][0]["lights"] = "no_shadows";
    EXPECT_EQ(std::get<GltfSourceSpec>(parsed(scenario).sources[0].spec).lights,
              GltfLights::NoShadows);
    scenario["scene"]["sources"][0]["lights"] = "ignore";
    EXPECT_EQ(std::get<GltfSourceSpec>(parsed(scenario).sources[0].spec).lights,
              GltfLights::Ignore);
    scenario["scene"]["sources"][0]["lights"] = "off";
    expectError(scenario, "/scene/sources/0/lights", "expected one of");
}

}  // namespace
}  // namespace occsim
