// hzb and raster end to end through the GL device (both GPU-driven: commands written and drawn on
// the device), on the scenes that break careless depth pyramids and box tests, all in
// one flight: viewports of odd sizes, two camera cuts, a pass 4 mm above the ground with the near
// plane at 1 mm, the camera flying through large closed boxes, near/far of 10^-3/10^6, the scene
// 10^6 m from the origin, and both depth conventions. Every frame must have zero error pixels and
// zero missed objects, with boxes and with spheres, objects and nodes as units; raster draws no
// more objects than hzb.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "occsim/culling/registry/registry.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kAssets = fs::path(OCCSIM_SOURCE_DIR) / "scenarios/assets";

json at(const glm::dvec3& o, double x, double y, double z) { return {o.x + x, o.y + y, o.z + z}; }

json trapScene(uint32_t width, uint32_t height, const glm::dvec3& o, bool conventional,
               const json& hzb_options) {
    const double near = conventional ? 0.05 : 1e-3, far = conventional ? 2000.0 : 1e6;
    const double low = conventional ? 0.2 : 0.004;  // eye height of the low pass
    json s = {
        {"format_version", 1},
        {"name", "hzb-traps"},
        {"seed", 9},
        {"frames", 30},
        {"warmup_frames", 0},
        {"viewport",
         {{"width", width},
          {"height", height},
          {"depth", conventional ? "conventional_24" : "reverse_float"}}},
        {"camera",
         {{"fov_y", 70},
          {"near", near},
          {"far", far},
          {"keyframes",
           // Through the first big box, a cut to a view from behind the field, a cut to the
           // low pass over the ground.
           {{{"time", 0.0}, {"position", at(o, 0, 2, 8)}, {"target", at(o, 0, 2, -20)}},
            {{"time", 0.33}, {"position", at(o, 0.3, 2, -12)}, {"target", at(o, 0, 1.5, -40)}},
            {{"time", 0.331}, {"position", at(o, -10, 6, -70)}, {"target", at(o, 5, 0, -5)}},
            {{"time", 0.66}, {"position", at(o, -8, 5, -66)}, {"target", at(o, 5, 0, -5)}},
            {{"time", 0.661}, {"position", at(o, 0, low, -25)}, {"target", at(o, 1, low, -40)}},
            {{"time", 1.0}, {"position", at(o, 0, low, -30)}, {"target", at(o, 1, 0.5, -50)}}}}}},
        {"scene",
         {{"sources",
           {{{"type", "teapots"},
             {"count", 250},
             {"region", {{"min", at(o, -12, 0, -60)}, {"max", at(o, 12, 4, 0)}}},
             {"size", {0.5, 2.0}},
             {"tessellation", 3}},
            {{"type", "gltf"},
             {"path", (kAssets / "Box/box.gltf").string()},
             {"scale", 9},
             {"offset", at(o, 0, 2, -10)},
             {"replicate",
              {{"mode", "grid"}, {"count_x", 1}, {"count_z", 2}, {"spacing", 24}}}}}}}},
        {"movers", {{{"source", 0}, {"fraction", 0.3}, {"motion", "bounce"}, {"speed", {2, 6}}}}},
        {"culling",
         {{"algorithm", "hzb"},
          {"hzb", hzb_options},
          {"raster", hzb_options.contains("node_units")
                         ? json{{"node_units", hzb_options["node_units"]}}
                         : json::object()}}},
    };
    return s;
}

void expectZeroError(const json& scene, const std::string& what) {
    BenchOptions options;
    options.algorithms = {findCuller("vfc"), findCuller("hzb"), findCuller("raster")};
    options.measure_error = true;
    options.latency = {true, 4};
    const BenchResult result = runBenchmark(
        parseScenarioText(scene.dump(), fs::path(OCCSIM_SOURCE_DIR) / "x.json"), options);
    for (const RunRecord& r : result.runs) {
        EXPECT_EQ(r.summary.error_pixels_total, 0) << what << ": " << r.algorithm->name;
        EXPECT_EQ(r.summary.missed_objects_total, 0) << what << ": " << r.algorithm->name;
        EXPECT_GT(r.summary.objects_mean, 0.0) << what << ": " << r.algorithm->name;
    }
    ASSERT_EQ(result.runs.size(), 3u);
    EXPECT_LT(result.runs[1].summary.objects_mean, result.runs[0].summary.objects_mean)
        << what << ": hzb culls something";
    EXPECT_LE(result.runs[2].summary.objects_mean, result.runs[1].summary.objects_mean)
        << what << ": raster draws no more than hzb";
    for (const RunRecord& r : result.runs) {
        for (const FrameStats& f : r.frames) {
            if (r.algorithm->name != "vfc") {
                EXPECT_EQ(f.read_backs, 0u) << what << ": " << r.algorithm->name;
            }
        }
    }
}

TEST(HzbScenes, OddViewportsCutsNearSurfacesAndFarFromTheOriginKeepZeroError) {
    expectZeroError(trapScene(203, 117, {0, 0, 0}, false, json::object()), "203x117");
    expectZeroError(trapScene(17, 31, {1e6, 0, -1e6}, false, {{"sphere_bounds", true}}),
                    "17x31, 10^6 m away, spheres");
    expectZeroError(trapScene(129, 65, {1e6, 0, -1e6}, false, {{"node_units", true}}),
                    "129x65, 10^6 m away, nodes");
}

TEST(HzbScenes, TheConventional24BitDepthBufferKeepsZeroError) {
    expectZeroError(trapScene(161, 99, {0, 0, 0}, true, json::object()), "161x99 conventional");
    expectZeroError(trapScene(161, 99, {0, 0, 0}, true, {{"sphere_bounds", true}}),
                    "161x99 conventional, spheres");
}

}  // namespace
}  // namespace occsim
