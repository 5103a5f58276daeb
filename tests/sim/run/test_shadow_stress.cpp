// The shadow pass on the stress scenes (docs/views.md): a sun grazing the ground, a scene
// 10^6 m from the origin, the camera inside a caster's box. Light-frustum and receiver-masked
// caster culling, and the cullers in the light's view (masked's software buffer orthographic
// there) without and with the receiver mask, keep
// zero shadow error pixels and zero missed casters on every frame, with query cullers on the
// camera's view; far from the origin they draw what they draw at it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "error_bench.h"
#include "shifted_teapots.h"
#include "sim/scenario/view_overrides.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

using testing::kScenarios;

// The small teapot scenario moved by `by`, under `sun` (ELEVATION,AZIMUTH,MAP).
Scenario teapotsUnder(const std::string& sun, const glm::dvec3& by = glm::dvec3(0.0)) {
    Scenario scenario = testing::shiftedTeapots(by);
    replaceLightsWith(scenario, parseSun(sun));
    return scenario;
}

BenchResult shadowBench(const Scenario& scenario, ShadowCasterCulling casters,
                        uint32_t frames = 10) {
    BenchOptions options;
    for (const char* name : {"vfc", "chc", "statistical", "masked"}) {
        options.algorithms.push_back(findCuller(name));
    }
    options.measure_error = true;
    options.latency = {true, 8};
    options.frames = frames;
    options.shadow_casters = casters;
    return runBenchmark(scenario, options);
}

// Zero error of every kind on every frame, and a shadow pass on each.
void expectNoShadowError(const BenchResult& result, const std::string& what) {
    testing::expectNoErrorAndNoMiss(result);
    for (const RunRecord& run : result.runs) {
        for (const FrameStats& f : run.frames) {
            const std::string at =
                what + ": " + run.summary.label + " frame " + std::to_string(f.frame);
            EXPECT_GE(f.shadow_casters, 0) << at;
            EXPECT_EQ(f.shadow_error_pixels, 0) << at;
            EXPECT_EQ(f.missed_casters, 0) << at;
        }
    }
}

constexpr ShadowCasterCulling kEveryCasterCulling[] = {
    ShadowCasterCulling::LightFrustum, ShadowCasterCulling::ReceiverMask,
    ShadowCasterCulling::Culler, ShadowCasterCulling::CullerWithReceiverMask};

TEST(ShadowStress, ASunGrazingTheGroundKeepsZeroShadowError) {
    for (const ShadowCasterCulling casters : kEveryCasterCulling) {
        const BenchResult result = shadowBench(teapotsUnder("2,40,1024"), casters);
        expectNoShadowError(result, "a sun 2 degrees up");
        int64_t seen = 0;
        for (const FrameStats& f : result.runs[0].frames) seen += f.shadow_seen_casters;
        EXPECT_GT(seen, 0) << "long shadows are in view";
    }
}

TEST(ShadowStress, AMillionMetresFromTheOriginTheShadowPassIsTheSame) {
    for (const ShadowCasterCulling casters : kEveryCasterCulling) {
        const BenchResult here = shadowBench(teapotsUnder("35,120,1024"), casters);
        const BenchResult far = shadowBench(teapotsUnder("35,120,1024", {1e6, 0, -1e6}), casters);
        expectNoShadowError(far, "10^6 m out");
        for (size_t r = 0; r < here.runs.size(); ++r) {
            for (size_t f = 0; f < here.runs[r].frames.size(); ++f) {
                const FrameStats& a = here.runs[r].frames[f];
                const FrameStats& b = far.runs[r].frames[f];
                EXPECT_EQ(a.objects_drawn, b.objects_drawn) << f;
                EXPECT_EQ(a.shadow_seen_casters, b.shadow_seen_casters) << f;
                if (casters != ShadowCasterCulling::ReceiverMask) {
                    EXPECT_EQ(a.shadow_casters, b.shadow_casters) << f;
                }
            }
        }
    }
}

// The camera inside a building of the small city (looking out through its walls: the camera's
// pass sees the walls' inner faces): every caster of a shadow on them is still drawn.
TEST(ShadowStress, TheCameraInsideACastersBoxKeepsZeroShadowError) {
    Scenario scenario = parseScenarioFile(kScenarios / "city-small.json");
    replaceLightsWith(scenario, parseSun("40,70,1024"));
    const Scene scene = buildScene(scenario);
    const WorldState state = initialState(scene);
    // The tallest object's box: a building.
    uint32_t tallest = 0;
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        const Aabb& b = state.boxes[o];
        if (b.max.y - b.min.y > state.boxes[tallest].max.y - state.boxes[tallest].min.y)
            tallest = o;
    }
    const Aabb& box = state.boxes[tallest];
    const glm::dvec3 centre =
        0.5 * (glm::dvec3(box.min) + glm::dvec3(box.max)) + scene.culling_origin;
    scenario.camera.keyframes = {{0.0, centre, centre + glm::dvec3(1, -0.3, 0.2)},
                                 {1.0, centre, centre + glm::dvec3(-0.2, -0.3, 1)}};
    scenario.camera.loop = false;
    for (const ShadowCasterCulling casters : kEveryCasterCulling) {
        expectNoShadowError(shadowBench(scenario, casters, 8), "inside a building");
    }
}

}  // namespace
}  // namespace occsim
