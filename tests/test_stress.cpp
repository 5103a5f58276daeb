// Numerical traps, end to end through OSMesa (ctest label `stress`; the fast ones also run in the
// normal suite): a scene far from the world origin must cull exactly as it does at the origin,
// with zero error for every conservative algorithm.
#include "culling/algorithms.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace occsim {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kSmall = fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json";

json readJson(const fs::path& file) { return json::parse(std::ifstream(file)); }

void shiftPoint(json& p, const glm::dvec3& by) {
    for (int i = 0; i < 3; ++i) p[i] = p[i].get<double>() + by[i];
}

// The small teapot scenario with every position it holds moved by `by`.
Scenario shifted(const glm::dvec3& by) {
    json s = readJson(kSmall);
    for (json& key : s["camera"]["keyframes"]) {
        shiftPoint(key["position"], by);
        shiftPoint(key["target"], by);
    }
    for (json& source : s["scene"]["sources"]) {
        shiftPoint(source["region"]["min"], by);
        shiftPoint(source["region"]["max"], by);
    }
    s.erase("expect");
    return parseScenarioText(s.dump(), kSmall);
}

BenchResult benchAll(const Scenario& scenario) {
    BenchOptions options;
    for (const AlgorithmTraits& a : algorithms()) options.algorithms.push_back(&a);
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
            EXPECT_EQ(a.frames[f].objects_drawn, b.frames[f].objects_drawn) << name << " frame " << f;
            EXPECT_EQ(a.frames[f].visible_objects, b.frames[f].visible_objects) << name << " frame " << f;
            if (a.algorithm->conservative) {
                EXPECT_EQ(b.frames[f].error_pixels, 0) << name << " frame " << f;
            }
        }
    }
}

}  // namespace
}  // namespace occsim
