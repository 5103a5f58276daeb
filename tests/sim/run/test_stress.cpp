// Numerical traps, end to end through OSMesa (ctest label `stress`; the fast ones also run in the
// normal suite): a scene far from the world origin must cull exactly as it does at the origin,
// with zero error for every conservative algorithm.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "shifted_teapots.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kSmall = fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json";

json readJson(const fs::path& file) { return json::parse(std::ifstream(file)); }

// The small teapot scenario with every position it holds moved by `by`.
Scenario shifted(const glm::dvec3& by) { return testing::shiftedTeapots(by); }

BenchResult benchAll(const Scenario& scenario) {
    BenchOptions options;
    options.algorithms = cullerRows();
    options.measure_error = true;
    options.latency = {true, 8};
    return runBenchmark(scenario, options);
}

// A million metres from the origin a float has 6 cm steps: boxes, tree and frustum in world
// coordinates would round differently there than at the origin. In the culling frame (relative
// to the scene's own origin) they do not, and the decisions are the same frame by frame.
TEST(FarFromTheOrigin, AScenarioMovedByAMillionMetresMakesTheSameDecisionsWithZeroError) {
    const BenchResult here = benchAll(shifted({0, 0, 0}));
    const BenchResult far = benchAll(shifted({1e6, 0, -1e6}));
    ASSERT_EQ(here.runs.size(), far.runs.size());
    for (size_t c = 0; c < here.runs.size(); ++c) {
        const RunRecord& a = here.runs[c];
        const RunRecord& b = far.runs[c];
        const std::string name(a.algorithm->name);
        ASSERT_EQ(a.frames.size(), b.frames.size());
        for (size_t f = 0; f < a.frames.size(); ++f) {
            EXPECT_EQ(a.frames[f].queries, b.frames[f].queries) << name << " frame " << f;
            EXPECT_EQ(a.frames[f].objects_drawn, b.frames[f].objects_drawn)
                << name << " frame " << f;
            EXPECT_EQ(a.frames[f].visible_objects, b.frames[f].visible_objects)
                << name << " frame " << f;
            if (a.algorithm->conservative) {
                EXPECT_EQ(b.frames[f].error_pixels, 0) << name << " frame " << f;
            }
        }
    }
}

// A billion seconds (32 years) into a simulation, a double still resolves 0.1 microseconds; every
// decision that uses time must come out as it does from 0.
TEST(LongTime, AScenarioStartedAtABillionSecondsMakesTheSameDecisionsAsFromZero) {
    json s = readJson(kSmall);
    s.erase("expect");
    const BenchResult from_zero = benchAll(parseScenarioText(s.dump(), kSmall));
    s["start_time"] = 1e9;
    const BenchResult late = benchAll(parseScenarioText(s.dump(), kSmall));
    for (size_t c = 0; c < from_zero.runs.size(); ++c) {
        const RunRecord& a = from_zero.runs[c];
        const RunRecord& b = late.runs[c];
        const std::string name(a.algorithm->name);
        for (size_t f = 0; f < a.frames.size(); ++f) {
            EXPECT_EQ(a.frames[f].queries, b.frames[f].queries) << name << " frame " << f;
            EXPECT_EQ(a.frames[f].objects_drawn, b.frames[f].objects_drawn)
                << name << " frame " << f;
        }
        EXPECT_DOUBLE_EQ(b.frames.back().time_s, 1e9 + a.frames.back().time_s);
    }
}

// ---- Far geometry: nodes that reach far past the camera --------------------------------------

// Every conservative configuration drew every visible pixel and object on every frame, and drew
// something (a scene culled whole would have nothing to miss only if nothing were visible).
void expectConservativeExact(const BenchResult& result, const std::string& what) {
    for (const RunRecord& r : result.runs) {
        if (!r.algorithm->conservative) continue;
        const std::string name(r.algorithm->name);
        EXPECT_EQ(r.summary.error_pixels_total, 0) << what << ": " << name;
        EXPECT_EQ(r.summary.missed_objects_total, 0) << what << ": " << name;
        EXPECT_GT(r.summary.objects_mean, 0.0) << what << ": " << name;
    }
}

json smallWithout(const char* key) {
    json s = readJson(kSmall);
    s.erase("expect");
    s.erase(key);
    s["frames"] = 8;
    s["warmup_frames"] = 0;
    return s;
}

json teapotAt(const glm::dvec3& p) {
    return {{"type", "teapots"},
            {"count", 1},
            {"region", {{"min", {p.x, p.y, p.z}}, {"max", {p.x + 1, p.y + 1, p.z + 1}}}}};
}

// One teapot `distance` metres away along x, far beyond the far plane, beside the small teapot
// field: the root of the tree, and every node on the way to that teapot, is `distance` wide.
// Queries on those nodes used to be drawn grown by 10^-4 of their size (100 m at 10^6) while the
// near-plane rule looked at the box as given, so the eye, a few metres outside the field, sat
// inside the drawn root box, its query saw only far faces, and every query culler dropped the
// whole scene (a 130x "speedup" over frustum culling that was all error).
TEST(FarGeometry, ANodeReachingFarAwayNeverHidesWhatItContains) {
    for (const double distance : {1e6, 1e9, 1e12}) {
        json s = smallWithout("movers");
        s["camera"]["far"] = 100;  // the drawn root box's far faces all lie beyond it
        s["scene"]["sources"].push_back(teapotAt({distance, 0, -30}));
        const BenchResult result = benchAll(parseScenarioText(s.dump(), kSmall));
        expectConservativeExact(result, "a teapot at x = " + std::to_string(distance));
    }
}

// Objects spawned along a path that reaches 10^9 m (and 3 * 10^38, near the largest float): with
// the culling origin at the centre of the objects' start positions, the eye and frustum the
// cullers saw were floats metres apart; the origin follows the camera now.
TEST(FarGeometry, MoversSpawnedAlongAPathToTheEdgeOfFloatKeepZeroError) {
    for (const double reach : {1e9, 3e38}) {
        json s = smallWithout("movers");
        s["movers"] = json::array(
            {{{"source", 0},
              {"spawn", {{"count", 40}, {"shape", "box"}}},
              {"motion", "path"},
              {"speed", {1e3, 1e4}},
              {"waypoints", {{-5, 1, -10}, {reach, 1, -10}, {reach, 1, -14}, {-5, 1, -14}}}}});
        const Scenario scenario = parseScenarioText(s.dump(), kSmall);
        const Scene scene = buildScene(scenario);
        EXPECT_LT(glm::length(scene.culling_origin), 100.0) << "the origin stays at the camera";
        expectConservativeExact(benchAll(scenario), "a path reaching " + std::to_string(reach));
    }
}

Scenario withCamera(const fs::path& file, double near_m, double far_m, bool conventional_depth,
                    double eye_height = -1.0) {
    json s = readJson(file);
    s.erase("expect");
    s["camera"]["near"] = near_m;
    s["camera"]["far"] = far_m;
    if (eye_height >= 0) {
        for (json& key : s["camera"]["keyframes"]) key["position"][1] = eye_height;
    }
    if (conventional_depth) s["viewport"]["depth"] = "conventional_24";
    return parseScenarioText(s.dump(), file);
}

int64_t errorPixelsOfConservative(const BenchResult& result) {
    int64_t total = 0;
    for (const RunRecord& r : result.runs) {
        if (r.algorithm->conservative)
            total += r.summary.error_pixels_total + r.summary.missed_objects_total;
    }
    return total;
}

int64_t tiePixelsOfConservative(const BenchResult& result) {
    int64_t total = 0;
    for (const RunRecord& r : result.runs) {
        if (r.algorithm->conservative) total += r.summary.tie_pixels_total;
    }
    return total;
}

// Near 1 mm, far 1000 km. With reverse-Z into a float depth buffer every conservative algorithm
// still draws exactly what ground truth shows. With the conventional mapping into 24-bit depth
// (the trap) surfaces metres apart share one depth step, the draw order decides, and ground
// truth (every object in index order) and the culled frames (front to back) disagree: ties in
// depth (docs/error.md), the buffer's failure, not the culler's, so no error pixel and no miss.
TEST(DepthPrecision, ANearFarRatioOf10To9KeepsZeroErrorOnlyWithReverseZInFloat) {
    const fs::path teapots = kSmall;
    const BenchResult reverse = benchAll(withCamera(teapots, 1e-3, 1e6, false));
    EXPECT_EQ(errorPixelsOfConservative(reverse), 0);
    const BenchResult conventional = benchAll(withCamera(teapots, 1e-3, 1e6, true));
    EXPECT_GT(tiePixelsOfConservative(conventional), tiePixelsOfConservative(reverse))
        << "the trap must show without the fix";
    EXPECT_EQ(errorPixelsOfConservative(conventional), 0) << "a tie in depth is no error";
}

// The eye 3 mm above the library floor, near plane at 1 mm: the floor is a sliver in depth
// almost along the line of sight, and the near plane cuts the boxes of everything around the eye.
TEST(DepthPrecision, TheEyeMillimetresAboveASurfaceKeepsZeroError) {
    const fs::path library = fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/library-small.json";
    const BenchResult result = benchAll(withCamera(library, 1e-3, 100, false, 0.005));
    EXPECT_EQ(errorPixelsOfConservative(result), 0);
    for (const RunRecord& r : result.runs) EXPECT_GT(r.summary.objects_mean, 0.0);
}

}  // namespace
}  // namespace occsim
