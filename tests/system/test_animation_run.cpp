// Animated real content through the whole run, with OpenGL (issue 22): an animated box rises from
// behind a wall, and every conservative culler draws it on the first frame ground truth sees it;
// the animated scenario in scenarios/ shows no error for conservative cullers.
#include <gtest/gtest.h>

#include <algorithm>

#include "gltf_builder.h"
#include "occsim/culling/registry/registry.h"
#include "shell_command.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

namespace occsim {
namespace {

using namespace testing_gltf;

// A closed unit cube (-0.5 .. 0.5), counter-clockwise seen from outside.
int cubeMesh(GltfBuilder& b, const std::string& name) {
    const int p = b.vec3({{-.5f, -.5f, -.5f},
                          {.5f, -.5f, -.5f},
                          {.5f, .5f, -.5f},
                          {-.5f, .5f, -.5f},
                          {-.5f, -.5f, .5f},
                          {.5f, -.5f, .5f},
                          {.5f, .5f, .5f},
                          {-.5f, .5f, .5f}});
    const int i = b.indices({0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 4, 7, 0, 7, 3,
                             1, 2, 6, 1, 6, 5, 0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2});
    return b.mesh(name, json::array({GltfBuilder::primitive(p, i)}));
}

std::vector<const CullerRow*> conservativeAlgorithms() {
    std::vector<const CullerRow*> out;
    for (const CullerRow* a : cullerRows()) {
        if (a->conservative) out.push_back(a);
    }
    return out;
}

// A wall 12 m wide and 4 m tall at z = 0; behind it (z = -4) a 1 m box whose node rises from
// y = 0.5 to 7.5 in 2 s (LINEAR). The camera at eye height looks at the wall from z = 10.
Scenario risingBoxScenario(const TempDir& dir) {
    GltfBuilder b;
    const int cube = cubeMesh(b, "Cube");
    b.node({{"mesh", cube}, {"translation", {0, 2, 0}}, {"scale", {12, 4, 0.4}}});
    const int box = b.node({{"mesh", cube}, {"translation", {0, 0.5, -4}}});
    b.animation("Rise", {{box, "translation", "LINEAR", {0.0f, 2.0f}, {0, 0.5f, -4, 0, 7.5f, -4}}});
    dir.write("rising.gltf", b.text());
    const json scenario = {
        {"format_version", 1},
        {"name", "rising-box"},
        {"frames", 60},
        {"dt", 1.0 / 30.0},
        {"viewport", {{"width", 160}, {"height", 120}}},
        {"camera",
         {{"near", 0.1},
          {"far", 100},
          {"keyframes", {{{"time", 0}, {"position", {0, 1.7, 10}}, {"target", {0, 1.7, 0}}}}}}},
        {"scene",
         {{"sources",
           {{{"type", "gltf"}, {"path", "rising.gltf"}, {"animation", {{"mode", "clamp"}}}}}}}},
        {"bsp", {{"max_objects_per_leaf", 1}}}};
    return parseScenarioFile(dir.write("rising.json", scenario.dump()));
}

void expectNoConservativeMisses(const BenchResult& result, const std::string& mode) {
    for (const RunRecord& run : result.runs) {
        // The frame ground truth first sees the box: one visible object (the wall) before it.
        uint32_t emerges = 0;
        for (const FrameStats& f : run.frames) {
            if (f.visible_objects == 2) {
                emerges = f.frame;
                break;
            }
        }
        ASSERT_GT(emerges, 0u) << run.summary.label << ": the box must start hidden and emerge";
        EXPECT_EQ(run.frames[emerges - 1].visible_objects, 1);
        EXPECT_GE(run.frames[emerges].moved_objects, 1u) << "the animated box is a mover";
        for (const FrameStats& f : run.frames) {
            EXPECT_EQ(f.missed_objects, 0)
                << run.summary.label << " (" << mode << ") frame " << f.frame
                << (f.frame == emerges ? ", the first the box is seen" : "");
            EXPECT_EQ(f.error_pixels, 0)
                << run.summary.label << " (" << mode << ") frame " << f.frame;
        }
    }
}

TEST(AnimationRun, ABoxRisingFromBehindAWallIsDrawnOnTheFirstFrameItIsSeen) {
    TempDir dir;
    const Scenario scenario = risingBoxScenario(dir);
    BenchOptions options;
    options.algorithms = conservativeAlgorithms();
    options.measure_error = true;
    expectNoConservativeMisses(runBenchmark(scenario, options), "measured latency");
    options.latency = LatencyMode{true, 8};
    expectNoConservativeMisses(runBenchmark(scenario, options), "deterministic latency 8");
}

TEST(AnimationRun, TheAnimatedScenarioShowsNoErrorForConservativeCullers) {
    BenchOptions options;
    options.algorithms = conservativeAlgorithms();
    options.measure_error = true;
    options.latency = LatencyMode{true, 8};
    const BenchResult result =
        runBenchmark(parseScenarioFile(std::filesystem::path(OCCSIM_SOURCE_DIR) /
                                       "scenarios/gltf-animated.json"),
                     options);
    for (const RunRecord& run : result.runs) {
        uint64_t moved = 0;
        for (const FrameStats& f : run.frames) {
            EXPECT_EQ(f.error_pixels, 0) << run.summary.label << " frame " << f.frame;
            EXPECT_EQ(f.missed_objects, 0) << run.summary.label << " frame " << f.frame;
            moved += f.moved_objects;
        }
        EXPECT_EQ(moved, 77u * 89u) << "every animated and moving object counts on every step";
    }
}

// Through the executable: a file the glTF specification forbids, and playback keys that do not
// fit the file, end with one line naming the place and exit code 2; `info` lists the animations.
TEST(AnimationCli, BadAnimationsAreOneLineWithExitCode2AndInfoListsAnimations) {
    TempDir dir;
    GltfBuilder b;
    b.node({{"mesh", b.triangleMesh("Tri")}});
    b.animation("Wobble", {{0, "rotation", "LINEAR", {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0}, "VEC3"}});
    dir.write("bad.gltf", b.text());
    const json camera = {
        {"keyframes", {{{"time", 0}, {"position", {0, 2, 10}}, {"target", {0, 0, 0}}}}}};
    const json bad_file = {{"format_version", 1},
                           {"name", "bad"},
                           {"camera", camera},
                           {"scene", {{"sources", {{{"type", "gltf"}, {"path", "bad.gltf"}}}}}}};
    const std::string exe = OCCSIM_EXE;
    testing::Outcome o =
        testing::shell(exe + " info " + dir.write("bad.json", bad_file.dump()).string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(
        o.output.find(
            "bad.gltf: /animations/0/samplers/0/output: a rotation output must be VEC4, got VEC3"),
        std::string::npos)
        << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;

    const std::string box =
        std::string(OCCSIM_SOURCE_DIR) + "/scenarios/assets/BoxAnimated/BoxAnimated.gltf";
    const json bad_play = {
        {"format_version", 1},
        {"name", "bad"},
        {"camera", camera},
        {"scene",
         {{"sources",
           {{{"type", "gltf"}, {"path", box}, {"animation", {{"play", json::array({5})}}}}}}}}};
    o = testing::shell(exe + " info " + dir.write("play.json", bad_play.dump()).string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find("/scene/sources/0/animation/play/0: expected an animation index < 2"),
              std::string::npos)
        << o.output;

    o = testing::shell(exe + " info " + std::string(OCCSIM_SOURCE_DIR) +
                       "/scenarios/gltf-animated.json");
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(
        o.output.find("animations    source 0: 2 animations, 42 animated copies of 2 objects"),
        std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("node 0 translation, LINEAR, 4 keys"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("3.708 s, plays"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("moves 1 object of each copy (1)"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace occsim
