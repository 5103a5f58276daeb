// A scenario's shadow maps against the device's largest texture (sim/run/light_limits.h): one
// that does not fit is one error naming the file, the light's key and the limit; a light that
// casts no shadow needs no map; a run on the machine's own device refuses, before frame 0, a map
// one texel larger than the device's largest texture.
#include <gtest/gtest.h>

#include "occsim/culling/registry/registry.h"
#include "render/headless_context.h"
#include "sim/run/light_limits.h"
#include "sim/run/runner.h"
#include "small_bench.h"

namespace occsim {
namespace {

Scenario withLights(std::initializer_list<uint32_t> sizes) {
    Scenario s;
    s.file = "scenarios/lit.json";
    for (const uint32_t size : sizes) {
        LightSpec light;
        light.shadow_map = size;
        s.lights.push_back(light);
    }
    return s;
}

TEST(LightLimits, AShadowMapLargerThanTheDevicesLargestTextureIsOneErrorNamingTheKey) {
    EXPECT_NO_THROW(checkShadowMapsFit(withLights({}), 1024));
    EXPECT_NO_THROW(checkShadowMapsFit(withLights({1024, 512}), 1024));
    try {
        checkShadowMapsFit(withLights({1024, 4096}), 2048);
        FAIL() << "expected a ScenarioError";
    } catch (const ScenarioError& e) {
        EXPECT_STREQ(e.what(),
                     "scenarios/lit.json: /lights/1/shadow_map: expected at most 2048 (this "
                     "device's largest texture, a side in texels), got 4096");
    }
    Scenario unlit = withLights({4096});
    unlit.lights[0].casts_shadows = false;
    EXPECT_NO_THROW(checkShadowMapsFit(unlit, 2048)) << "no shadow pass, no map";
}

// The run checks before frame 0 with its device's own limit (GL_MAX_TEXTURE_SIZE, in
// ContextInfo): one texel more is refused with the one line, the limit itself runs.
TEST(LightLimits, TheRunRefusesAMapLargerThanItsDevicesLargestTextureBeforeFrame0) {
    uint32_t limit = 0;
    {
        const auto context = createHeadlessContext(BackendChoice{}, 16, 16);
        limit = context->info().max_texture_size;
    }
    ASSERT_GE(limit, 1024u) << "OpenGL 4.5 guarantees 16384; a driver may say less";
    Scenario s = parseScenarioFile(testing::kSmall);
    s.lights.push_back(LightSpec{});
    BenchOptions options;
    options.algorithms = testing::traitsOf({"vfc"});
    options.frames = 2;
    options.on_note = [](const std::string&) {};
    s.lights[0].shadow_map = limit + 1;
    try {
        runBenchmark(s, options);
        FAIL() << "expected the run refused";
    } catch (const ScenarioError& e) {
        EXPECT_NE(std::string(e.what()).find("teapots-small.json: /lights/0/shadow_map: expected "
                                             "at most " +
                                             std::to_string(limit)),
                  std::string::npos)
            << e.what();
    }
    s.lights[0].shadow_map = 1024;
    EXPECT_EQ(runBenchmark(s, options).metadata.frames, 2u);
}

}  // namespace
}  // namespace occsim
