// The command line's sun (sim/scenario/sun_override.h): its direction from the elevation and
// azimuth, its shadow map, what is refused, and that it is the scene's one light.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <stdexcept>

#include "sim/scenario/sun_override.h"

namespace occsim {
namespace {

TEST(SunOverride, ElevationAndAzimuthGiveTheWayTheLightTravels) {
    const LightSpec noon = parseSun("90,0");
    EXPECT_EQ(noon.type, LightType::Directional);
    EXPECT_TRUE(noon.casts_shadows);
    EXPECT_NEAR(glm::length(noon.direction - glm::dvec3(0, -1, 0)), 0.0, 1e-12);
    EXPECT_EQ(noon.shadow_map, LightSpec{}.shadow_map);
    // 30 degrees up, shining from +z (azimuth 90): it travels toward -z and down.
    const LightSpec low = parseSun("30,90,1024");
    EXPECT_NEAR(low.direction.x, 0.0, 1e-12);
    EXPECT_NEAR(low.direction.y, -0.5, 1e-12);
    EXPECT_NEAR(low.direction.z, -std::sqrt(3.0) / 2.0, 1e-12);
    EXPECT_EQ(low.shadow_map, 1024u);
}

TEST(SunOverride, WhatIsNoSunIsRefusedSayingWhatWasExpected) {
    for (const char* bad : {"", "30", "30,", "0,10", "-5,10", "91,10", "nan,10", "30,inf",
                            "30,10,0", "30,10,1.5", "30,10,99999", "30,10,1024,1", "a,b"}) {
        try {
            parseSun(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("expected ELEVATION,AZIMUTH[,SHADOW_MAP]"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(SunOverride, ItIsTheScenesOneLight) {
    Scenario scenario;
    scenario.lights = {LightSpec{}, LightSpec{}};
    SceneSourceSpec gltf;
    gltf.type = SourceType::Gltf;
    gltf.spec = GltfSourceSpec{};
    scenario.sources = {SceneSourceSpec{}, gltf};
    replaceLightsWith(scenario, parseSun("20,45"));
    ASSERT_EQ(scenario.lights.size(), 1u);
    EXPECT_NEAR(scenario.lights[0].direction.y, -std::sin(glm::radians(20.0)), 1e-12);
    EXPECT_EQ(std::get<GltfSourceSpec>(scenario.sources[1].spec).lights, GltfLights::Ignore);
}

}  // namespace
}  // namespace occsim
