// The command line's views (sim/scenario/view_overrides.h): the sun's direction from the elevation
// and azimuth, its shadow map, what is refused, and that it is the scene's one light; stereo's
// separation and mode, and what is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <stdexcept>

#include "sim/scenario/view_overrides.h"

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

TEST(StereoOverride, SeparationAndModeAreRead) {
    const StereoSpec ipd = parseStereo("0.064");
    EXPECT_EQ(ipd.eye_separation_m, 0.064);
    EXPECT_EQ(ipd.culling, StereoCulling::Enclosing);
    EXPECT_EQ(parseStereo("2,enclosing").culling, StereoCulling::Enclosing);
    const StereoSpec per_eye = parseStereo("0.07,per_eye");
    EXPECT_EQ(per_eye.eye_separation_m, 0.07);
    EXPECT_EQ(per_eye.culling, StereoCulling::PerEye);
}

TEST(StereoOverride, WhatIsNoStereoIsRefusedSayingWhatWasExpected) {
    for (const char* bad : {"", "0", "-0.06", "nan", "inf", "0.06,", "0.06,both", "0.06,per_eye,1",
                            "a", ",per_eye"}) {
        try {
            parseStereo(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("expected SEPARATION[,MODE]"), std::string::npos)
                << e.what();
        }
    }
}

}  // namespace
}  // namespace occsim
