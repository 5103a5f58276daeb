// A glTF file's KHR_lights_punctual lights (sim/scene/gltf_lights.cpp): directional and spot
// lights at their nodes' world transforms (a light shines down its node's -z), scaled, moved and
// replicated with the model (the sun once, a spot light per copy); the source's "lights" key; a
// point light, a light index out of range and a node naming no light are one error naming the
// file.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gltf_builder.h"
#include "sim/scenario/errors.h"
#include "sim/scene/gltf_source.h"

namespace occsim {
namespace {

using namespace testing_gltf;

// A triangle, a sun tilted 45 degrees about x (down -z turned toward -y), and a spot light 3 m up
// pointing straight down, with a cone of pi/8 and a range of 20.
std::string litModel(const std::string& spot_type = "spot") {
    GltfBuilder b;
    b.node({{"mesh", b.triangleMesh("Tri")}});
    const double s = std::sin(-M_PI / 8), c = std::cos(-M_PI / 8);  // -45 degrees about x
    b.node({{"rotation", {s, 0, 0, c}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    const double d = std::sqrt(0.5);  // -90 degrees about x: -z turns to -y
    b.node({{"translation", {1, 3, 0}},
            {"rotation", {-d, 0, 0, d}},
            {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    b.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc()["extensions"] = {{"KHR_lights_punctual",
                              {{"lights",
                                {{{"type", "directional"}, {"name", "sun"}},
                                 {{"type", spot_type},
                                  {"name", "lamp"},
                                  {"range", 20},
                                  {"spot", {{"outerConeAngle", M_PI / 8}}}}}}}}};
    return b.text();
}

SourceOutput loadWith(const std::string& text, GltfLights lights, double scale = 1.0,
                      glm::dvec3 offset = glm::dvec3(0.0), GltfReplication replicate = {}) {
    TempDir dir;
    GltfSourceSpec spec;
    spec.path = dir.write("lit.gltf", text);
    spec.scale = scale;
    spec.offset = offset;
    spec.replicate = replicate;
    spec.lights = lights;
    return loadGltfSource(spec, 1);
}

std::string errorOf(const std::string& text) {
    try {
        loadWith(text, GltfLights::Shadows);
    } catch (const GltfError& e) {
        return e.what();
    }
    return "";
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b) {
    EXPECT_NEAR(glm::length(a - b), 0.0, 1e-9) << a.x << " " << a.y << " " << a.z;
}

TEST(GltfLights, ASunAndASpotLightAtTheirNodesWorldTransforms) {
    const SourceOutput out = loadWith(litModel(), GltfLights::Shadows, 2.0, {100, 0, 0});
    ASSERT_EQ(out.lights.size(), 2u);
    const LightSpec& sun = out.lights[0];
    EXPECT_EQ(sun.type, LightType::Directional);
    expectNear(sun.direction, glm::dvec3(0, -std::sqrt(0.5), -std::sqrt(0.5)));
    EXPECT_TRUE(sun.casts_shadows) << "the sun casts the scene's shadows";
    const LightSpec& spot = out.lights[1];
    EXPECT_EQ(spot.type, LightType::Spot);
    expectNear(spot.direction, glm::dvec3(0, -1, 0));
    expectNear(spot.position, glm::dvec3(102, 6, 0));  // scaled by 2, then moved by the offset
    EXPECT_NEAR(spot.outer_cone_deg, 22.5, 1e-9);
    EXPECT_NEAR(spot.range_m, 40.0, 1e-9) << "scaled with the model";
    EXPECT_FALSE(spot.casts_shadows);
}

TEST(GltfLights, TheSourceKeySaysWhetherTheyCastOrAreLeftOut) {
    const SourceOutput unshadowed = loadWith(litModel(), GltfLights::NoShadows);
    ASSERT_EQ(unshadowed.lights.size(), 2u);
    EXPECT_FALSE(unshadowed.lights[0].casts_shadows);
    EXPECT_TRUE(loadWith(litModel(), GltfLights::Ignore).lights.empty());
    EXPECT_TRUE(loadWith(litModel("point"), GltfLights::Ignore).lights.empty())
        << "a point light is no error when the lights are left out";
}

TEST(GltfLights, ReplicatedTheSunOnceAndASpotLightPerCopy) {
    GltfReplication grid;
    grid.mode = GltfReplication::Mode::Grid;
    grid.count_x = 2;
    grid.count_z = 3;
    grid.spacing_m = 10.0;
    const SourceOutput out = loadWith(litModel(), GltfLights::Shadows, 1.0, {0, 0, 0}, grid);
    ASSERT_EQ(out.lights.size(), 1u + 6u);
    EXPECT_EQ(out.lights[0].type, LightType::Directional);
    ASSERT_EQ(out.model_copies.size(), 6u);
    for (size_t k = 0; k < 6; ++k) {
        EXPECT_EQ(out.lights[1 + k].type, LightType::Spot);
        expectNear(out.lights[1 + k].position, out.model_copies[k].origin + glm::dvec3(1, 3, 0));
    }
}

TEST(GltfLights, UnsupportedOrBrokenLightsAreOneErrorNamingTheFile) {
    std::string error = errorOf(litModel("point"));
    EXPECT_NE(error.find("lit.gltf: light 1 ('lamp') is a point light; occsim reads directional "
                         "and spot lights only"),
              std::string::npos)
        << error;
    EXPECT_NE(error.find("\"lights\": \"ignore\""), std::string::npos) << error;
    json doc = json::parse(litModel());
    doc["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 7;
    error = errorOf(doc.dump());
    EXPECT_NE(error.find("node 1 refers to light 7, but the file has 2 lights"), std::string::npos)
        << error;
    doc["nodes"][1]["extensions"]["KHR_lights_punctual"] = json::object();
    error = errorOf(doc.dump());
    EXPECT_NE(error.find("node 1's KHR_lights_punctual names no light"), std::string::npos)
        << error;
}

}  // namespace
}  // namespace occsim
