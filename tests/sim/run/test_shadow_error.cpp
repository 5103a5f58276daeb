// The shadow term's error (sim/run/shadow_error.h, docs/views.md): the counts on planted
// buffers, a planted tie in the maps; on a real run of a city under a low sun, light-frustum
// culling misses no caster and no shadow pixel while ground truth sees shadows, the camera's
// figures are those of the run without the light; and a caster left out of the shadow pass shows as
// shadow error pixels and one missed caster, so the zero above can fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

#include "depth_conventions.h"
#include "error_bench.h"
#include "render/gl_shadow_map.h"
#include "sim/run/ground_truth.h"
#include "sim/run/shadow_error.h"
#include "sim/run/shared_world.h"
#include "sim/run/simulation.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

using testing::kScenarios;

TEST(ShadowError, CountsPixelsOfTheSameObjectWhoseLitStateDiffers) {
    // Pixel 0: same object, both lit; 1: same object, shadowed in truth only (error); 2: same
    // object, shadowed by different texels (no error: both shadowed); 3: another object (the
    // camera view's business); 4: background in both.
    const std::vector<uint32_t> truth_ids = {1, 1, 2, 3, 0}, culled_ids = {1, 1, 2, 4, 0};
    const std::vector<uint32_t> truth_texels = {0, 7, 9, 5, 0}, culled_texels = {0, 0, 8, 0, 0};
    const ShadowPixelCounts counts =
        compareShadowTerms(truth_ids, truth_texels, culled_ids, culled_texels);
    EXPECT_EQ(counts.error, 1);
    EXPECT_EQ(counts.tie, 0);
    EXPECT_EQ(compareShadowTerms(truth_ids, truth_texels, truth_ids, truth_texels).error, 0);
    EXPECT_THROW(compareShadowTerms(truth_ids, truth_texels, culled_ids, {}),
                 std::invalid_argument);
}

// A planted tie: ground truth's caster at texel 6 (pixel 1's) left out, and another one float step
// behind it in the culled map. Pixel 1 is lit in the culled frame only because of that step: a
// tie. Two steps behind, or a texel the culled map left empty, it is an error; pixel 2 is
// shadowed only in the culled frame, by texel 3, which the maps agree on within a step.
TEST(ShadowError, ACasterOneDepthStepFromGroundTruthsIsATie) {
    const std::vector<uint32_t> ids = {1, 1, 2}, truth_texels = {0, 7, 0},
                                culled_texels = {0, 0, 4};
    std::vector<float> truth_map(8, 0.5f), culled_map(8, 0.5f);
    culled_map[6] = std::nextafter(0.5f, 1.0f);
    culled_map[3] = std::nextafter(0.5f, 0.0f);
    ShadowPixelCounts counts =
        compareShadowTerms(ids, truth_texels, ids, culled_texels, truth_map, culled_map);
    EXPECT_EQ(counts.tie, 2);
    EXPECT_EQ(counts.error, 0);
    culled_map[6] = std::nextafter(culled_map[6], 1.0f);
    counts = compareShadowTerms(ids, truth_texels, ids, culled_texels, truth_map, culled_map);
    EXPECT_EQ(counts.tie, 1);
    EXPECT_EQ(counts.error, 1);
    culled_map[6] = 1.0f;  // nothing there (the conventional far value)
    counts = compareShadowTerms(ids, truth_texels, ids, culled_texels, truth_map, culled_map);
    EXPECT_EQ(counts.error, 1);
    // Without the maps, every difference is an error.
    counts = compareShadowTerms(ids, truth_texels, ids, culled_texels);
    EXPECT_EQ(counts.error, 2);
    EXPECT_EQ(counts.tie, 0);
}

TEST(ShadowError, ACasterIsMissedWhenItsShadowIsSeenAndItWasNotDrawn) {
    const std::vector<uint32_t> seen = {7, 0, 1, 30};  // shadow pixels per caster
    const std::vector<uint8_t> drawn = {1, 1, 0};
    EXPECT_EQ(countMissedCasters(seen, drawn), 2);  // object 2 not drawn, object 3 past `drawn`
    EXPECT_EQ(countMissedCasters(seen, std::vector<uint8_t>{1, 0, 1, 1}), 0);
}

// city-small under a low sun from the side: tall buildings shade the streets the camera sees.
Scenario litCity(DepthConvention depth = DepthConvention::ReverseFloat) {
    Scenario scenario = parseScenarioFile(kScenarios / "city-small.json");
    LightSpec sun;
    sun.direction = glm::normalize(glm::dvec3(1.0, -0.35, 0.25));
    sun.shadow_map = 1024;
    scenario.lights.push_back(sun);
    scenario.conventional_depth = depth == DepthConvention::Conventional24;
    return scenario;
}

// A bench of these cullers on litCity(): error measured, deterministic latency, 12 frames.
BenchOptions litCityBench(std::initializer_list<const char*> cullers) {
    return testing::errorBenchOf(cullers, 12);
}

TEST(ShadowError, LightFrustumCullingMissesNoCasterAndLeavesTheCameraFiguresAlone) {
    BenchOptions options;
    for (const char* name : {"vfc", "chc", "hzb"}) options.algorithms.push_back(findCuller(name));
    options.measure_error = true;
    options.latency = {true, 8};
    options.frames = 12;
    const BenchResult lit = runBenchmark(litCity(), options);
    const BenchResult plain =
        runBenchmark(parseScenarioFile(kScenarios / "city-small.json"), options);
    testing::expectNoErrorAndNoMiss(lit);
    ASSERT_EQ(lit.runs.size(), plain.runs.size());
    int64_t seen = 0;
    for (size_t r = 0; r < lit.runs.size(); ++r) {
        const std::string& label = lit.runs[r].summary.label;
        for (size_t f = 0; f < lit.runs[r].frames.size(); ++f) {
            const FrameStats& s = lit.runs[r].frames[f];
            EXPECT_GT(s.shadow_casters, 0) << label << " frame " << f;
            EXPECT_GE(s.shadow_cpu_ms, 0.0);
            EXPECT_EQ(s.shadow_error_pixels, 0) << label << " frame " << f;
            EXPECT_EQ(s.shadow_tie_pixels, 0) << label << " frame " << f;
            EXPECT_EQ(s.missed_casters, 0) << label << " frame " << f;
            EXPECT_LE(s.shadow_seen_casters, s.shadow_casters) << label << " frame " << f;
            seen += s.shadow_seen_casters;
            // The camera's culling and error are the same as without the light.
            const FrameStats& p = plain.runs[r].frames[f];
            EXPECT_EQ(s.objects_drawn, p.objects_drawn) << label << " frame " << f;
            EXPECT_EQ(s.queries, p.queries) << label << " frame " << f;
            EXPECT_EQ(s.visible_objects, p.visible_objects) << label << " frame " << f;
            EXPECT_EQ(p.shadow_casters, -1);
            EXPECT_EQ(p.shadow_error_pixels, -1);
        }
        EXPECT_EQ(lit.runs[r].summary.missed_casters_total, 0) << label;
        EXPECT_GT(lit.runs[r].summary.shadow_casters_mean, 0.0) << label;
    }
    EXPECT_GT(seen, 0) << "ground truth shows no shadow: the check above proves nothing";
}

// Receiver-masked caster culling (sim/world/receiver_mask.h) on the same runs: no shadow error
// and no missed caster on any frame, never more casters than light-frustum culling and fewer on
// most frames, never fewer than ground truth shows; the camera's decisions as before. A culler
// whose draws the device decides is refused with one line.
TEST(ShadowError, ReceiverMaskedCullingMissesNoCasterAndDrawsFewer) {
    BenchOptions options = litCityBench({"vfc", "statistical", "chc", "conditional", "masked"});
    const BenchResult frustum = runBenchmark(litCity(), options);
    options.shadow_casters = ShadowCasterCulling::ReceiverMask;
    const BenchResult masked = runBenchmark(litCity(), options);
    testing::expectNoErrorAndNoMiss(masked);
    for (size_t r = 0; r < masked.runs.size(); ++r) {
        const std::string& label = masked.runs[r].summary.label;
        uint32_t fewer = 0;
        for (size_t f = 0; f < masked.runs[r].frames.size(); ++f) {
            const FrameStats& m = masked.runs[r].frames[f];
            const FrameStats& l = frustum.runs[r].frames[f];
            EXPECT_EQ(m.shadow_error_pixels, 0) << label << " frame " << f;
            EXPECT_EQ(m.missed_casters, 0) << label << " frame " << f;
            EXPECT_LE(m.shadow_casters, l.shadow_casters) << label << " frame " << f;
            EXPECT_GE(m.shadow_casters, m.shadow_seen_casters) << label << " frame " << f;
            EXPECT_EQ(m.objects_drawn, l.objects_drawn) << label << " frame " << f;
            EXPECT_GE(m.shading_cpu_ms, 0.0) << "the shading pass is timed";
            EXPECT_EQ(l.shading_cpu_ms, -1.0) << "light-frustum culling has none";
            fewer += m.shadow_casters < l.shadow_casters;
        }
        EXPECT_GT(fewer, masked.runs[r].frames.size() / 2) << label;
    }
    options.algorithms = {findCuller("hzb")};
    EXPECT_THROW(runBenchmark(litCity(), options), InputError);
}

// The light's view culled by each configuration's culler (ShadowCasterCulling::Culler), alone and
// with the receiver mask leaving out casters that may shadow no visible receiver
// (CullerWithReceiverMask): no shadow error and no missed caster on any frame; the camera's
// decisions as with light-frustum culling (the light's culler is an instance of its own: its
// state does not touch the camera's); vfc in the light's view draws every caster light-frustum
// culling draws (its frustum is the light's box), a culler that waits for each query fewer on
// most frames under a low sun (the buildings hide one another from it); with the mask, fewer
// casters over the run than with either alone; the same casters on a second run. Oracles and
// cullers that rasterise the camera's view or decide on the device are refused with one line.
// masked in the light's view: its software buffer rasterises the casters through the light's
// orthographic projection (MaskedDepthBuffer::beginOrthographicFrame) and hides casters behind
// them, without and with the receiver mask: no shadow error, no missed caster, and fewer casters
// than light-frustum culling draws.
TEST(ShadowError, MaskedCullsTheLightsViewWithNoShadowErrorAndDrawsFewerCasters) {
    BenchOptions options = litCityBench({"masked"});
    const BenchResult frustum = runBenchmark(litCity(), options);
    for (const ShadowCasterCulling casters :
         {ShadowCasterCulling::Culler, ShadowCasterCulling::CullerWithReceiverMask}) {
        options.shadow_casters = casters;
        const BenchResult culled = runBenchmark(litCity(), options);
        testing::expectNoErrorAndNoMiss(culled);
        int64_t culled_total = 0, frustum_total = 0, seen = 0;
        for (size_t f = 0; f < culled.runs[0].frames.size(); ++f) {
            const FrameStats& c = culled.runs[0].frames[f];
            EXPECT_EQ(c.shadow_error_pixels, 0) << "frame " << f;
            EXPECT_EQ(c.missed_casters, 0) << "frame " << f;
            EXPECT_EQ(c.objects_drawn, frustum.runs[0].frames[f].objects_drawn) << "frame " << f;
            culled_total += c.shadow_casters;
            frustum_total += frustum.runs[0].frames[f].shadow_casters;
            seen += c.shadow_seen_casters;
        }
        EXPECT_GT(seen, 0) << "no shadow in view: the zeros above prove little";
        EXPECT_LT(culled_total, frustum_total) << "masked hid no caster from the light";
    }
}

TEST(ShadowError, CullersCullingTheLightsViewMissNoCasterAndDrawFewer) {
    BenchOptions options =
        litCityBench({"vfc", "stop-and-wait", "statistical", "chc", "conditional"});
    const BenchResult frustum = runBenchmark(litCity(), options);
    options.shadow_casters = ShadowCasterCulling::ReceiverMask;
    const BenchResult receivers = runBenchmark(litCity(), options);
    options.shadow_casters = ShadowCasterCulling::Culler;
    const BenchResult culled = runBenchmark(litCity(), options);
    const BenchResult again = runBenchmark(litCity(), options);
    options.shadow_casters = ShadowCasterCulling::CullerWithReceiverMask;
    const BenchResult both = runBenchmark(litCity(), options);
    testing::expectNoErrorAndNoMiss(culled);
    testing::expectNoErrorAndNoMiss(both);
    ASSERT_EQ(culled.runs.size(), frustum.runs.size());
    ASSERT_EQ(both.runs.size(), frustum.runs.size());
    for (size_t r = 0; r < culled.runs.size(); ++r) {
        const std::string& label = culled.runs[r].summary.label;
        uint32_t fewer = 0;
        int64_t culled_total = 0, receivers_total = 0, both_total = 0;
        int64_t culled_queries = 0, both_queries = 0;
        for (size_t f = 0; f < culled.runs[r].frames.size(); ++f) {
            const FrameStats& l = frustum.runs[r].frames[f];
            for (const BenchResult* result : {&culled, &both}) {
                const FrameStats& c = result->runs[r].frames[f];
                EXPECT_EQ(c.shadow_error_pixels, 0) << label << " frame " << f;
                EXPECT_EQ(c.missed_casters, 0) << label << " frame " << f;
                EXPECT_GE(c.shadow_casters, c.shadow_seen_casters) << label << " frame " << f;
                EXPECT_EQ(c.objects_drawn, l.objects_drawn) << label << " frame " << f;
                EXPECT_EQ(c.queries, l.queries) << label << " frame " << f;
            }
            const FrameStats& c = culled.runs[r].frames[f];
            EXPECT_EQ(c.shadow_casters, again.runs[r].frames[f].shadow_casters)
                << label << " frame " << f;
            if (label == "vfc") {
                EXPECT_GE(c.shadow_casters, l.shadow_casters) << "frame " << f;
            }
            fewer += c.shadow_casters < l.shadow_casters;
            culled_total += c.shadow_casters;
            receivers_total += receivers.runs[r].frames[f].shadow_casters;
            both_total += both.runs[r].frames[f].shadow_casters;
            culled_queries += c.shadow_queries;
            both_queries += both.runs[r].frames[f].shadow_queries;
        }
        // The mask on the queries' boxes: a node whose shadow falls on nothing visible is
        // answered hidden and its subtree never queried (fails without the query filter).
        if (label == "stop-and-wait" || label == "chc") {
            EXPECT_LT(both_queries, culled_queries) << label;
        }
        if (label == "stop-and-wait") {
            EXPECT_GT(fewer, culled.runs[r].frames.size() / 2);
        }
        EXPECT_LT(both_total, culled_total) << label;
        EXPECT_LE(both_total, receivers_total) << label;
    }
    for (const char* refused : {"hzb", "raster", "ideal-box"}) {
        options.algorithms = {findCuller(refused)};
        EXPECT_THROW(runBenchmark(litCity(), options), InputError) << refused;
    }
}

class PlantedShadowError : public ::testing::TestWithParam<DepthConvention> {};

TEST_P(PlantedShadowError, ACasterLeftOutOfTheShadowPassIsCounted) {
    const Scenario scenario = litCity(GetParam());
    const auto context = createHeadlessContext({}, scenario.width, scenario.height);
    const Scene scene = buildScene(scenario);
    GlRenderer renderer(scenario.width, scenario.height, GetParam());
    uploadScene(scene, renderer);
    SharedWorld world(scene, scenario);
    GroundTruth truth(renderer);
    world.advance();
    const GroundTruthFrame& frame = truth.of(world);
    ASSERT_TRUE(frame.has_shadow);
    // The caster whose shadow covers most visible pixels.
    const uint32_t objects = scene.objectCount();
    std::vector<uint32_t> shaded(objects, 0);
    const std::vector<uint32_t> casters = frame.shadow_casters;
    const std::vector<uint32_t> truth_ids = frame.ids, truth_texels = frame.shadow_texels;
    for (size_t i = 0; i < truth_ids.size(); ++i) {
        if (truth_ids[i] != 0 && truth_texels[i] != 0 && casters[truth_texels[i] - 1] != 0) {
            ++shaded[casters[truth_texels[i] - 1] - 1];
        }
    }
    const auto left_out =
        static_cast<uint32_t>(std::max_element(shaded.begin(), shaded.end()) - shaded.begin());
    ASSERT_GT(shaded[left_out], 20u);

    // The frame again with every object in the camera's pass, and every caster but that one in
    // the shadow pass.
    const ShadowView& shadow = *world.shadowView();
    GlShadowMap map(shadow.map_size);
    renderer.setView(shadow.render, shadow.model_views);
    map.begin(renderer);
    std::vector<uint8_t> drawn(objects, 1);
    drawn[left_out] = 0;
    for (uint32_t o = 0; o < objects; ++o) {
        if (drawn[o]) renderer.drawObject(o);
    }
    const ShadowLookup lookup =
        map.lookupFor(world.view().render, shadow.render, renderer.depthConvention());
    renderer.setView(world.view().render, world.modelViews());
    renderer.setShadow(&lookup);
    renderer.beginFrame();
    for (uint32_t o = 0; o < objects; ++o) renderer.drawObject(o);
    std::vector<uint32_t> ids, texels;
    renderer.readObjectIds(ids);
    renderer.readShadowTexels(texels);
    renderer.setShadow(nullptr);
    EXPECT_EQ(ids, truth_ids);
    EXPECT_GE(compareShadowTerms(truth_ids, truth_texels, ids, texels).error, 1);
    EXPECT_EQ(countMissedCasters(frame.shadow_pixels, drawn), 1);
    // With it drawn, the same frame has none.
    drawn[left_out] = 1;
    EXPECT_EQ(countMissedCasters(frame.shadow_pixels, drawn), 0);
}

INSTANTIATE_TEST_SUITE_P(Depth, PlantedShadowError, bothDepthConventions(), depthConventionName);

}  // namespace
}  // namespace occsim
