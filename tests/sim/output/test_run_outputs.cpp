// A run's files (sim/output/run_outputs.h): frames.csv, summary.json and the captured frames.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tuple>

#include "sim/output/pictures.h"
#include "sim/output/run_outputs.h"
#include "small_bench.h"

namespace occsim {
namespace {

using testing::freshDir;
using testing::kSmall;
using testing::traitsOf;

TEST(Simulation, WritesFramesCsvAndSummaryJsonAndCaptures) {
    BenchOptions options;
    options.algorithms = traitsOf({"statistical", "vfc"});
    options.measure_error = true;
    options.frames = 6;
    const std::filesystem::path out_dir = freshDir("outputs");
    PictureRecorder pictures(out_dir, {3}, std::nullopt);
    options.on_frame = [&pictures](const FrameEvent& e) { pictures.onFrame(e); };
    const BenchResult result = runBenchmark(parseScenarioFile(kSmall), options);
    writeRunOutputs(result, {out_dir, false, {}, {}, {}});
    std::ifstream csv(out_dir / "frames.csv");
    std::string line;
    int lines = 0;
    while (std::getline(csv, line)) {
        if (lines == 0) {
            EXPECT_NE(
                line.find(
                    ",error_pixels,tie_pixels,missed_objects,tied_away_objects,visible_objects"),
                std::string::npos)
                << line;
        }
        ++lines;
    }
    EXPECT_EQ(lines, 1 + 2 * 6);
    const auto summary = nlohmann::json::parse(std::ifstream(out_dir / "summary.json"));
    EXPECT_EQ(summary["algorithms"].size(), 2u);
    EXPECT_EQ(summary["algorithms"][0]["error"]["pixels_total"], 0);
    // The three figures of error, and what tells error from tie (docs/error.md).
    for (const char* key :
         {"tie_pixels_total", "tie_pixels_per_frame_mean", "frames_with_ties",
          "missed_objects_total", "tied_away_objects_total", "overdrawn_objects_per_frame_mean",
          "overdrawn_triangles_per_frame_mean"}) {
        EXPECT_TRUE(summary["algorithms"][0]["error"].contains(key)) << key;
    }
    EXPECT_EQ(summary["error_definition"]["tie_tolerance_depth_steps"], 1);
    EXPECT_EQ(summary["error_definition"]["depth_format"], "reverse-Z, 32-bit float");
    EXPECT_TRUE(summary["algorithms"][0].contains("speedup_over_vfc"));
    EXPECT_EQ(summary["scenario"]["objects"], 300);
    // The run's own work: one world advance and one ground-truth render per frame for both.
    const auto& costs = summary["simulator_costs"];
    EXPECT_EQ(costs["world_advances"], 6);
    EXPECT_EQ(costs["ground_truth_renders"], 6);
    EXPECT_EQ(costs["error_read_backs"], 12);
    for (const char* key : {"wall_ms_after_setup", "frame_ms_total", "world_update_ms_total",
                            "ground_truth_ms_total"}) {
        EXPECT_TRUE(costs[key].is_number()) << key;
    }
    EXPECT_TRUE(std::filesystem::exists(out_dir / "frame-00003-statistical.png"));
    EXPECT_TRUE(std::filesystem::exists(out_dir / "frame-00003-vfc.png"));
    EXPECT_EQ(pictures.captureFiles().size(), 2u);
    for (const auto& entry : std::filesystem::directory_iterator(out_dir)) {
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    }
}

}  // namespace
}  // namespace occsim
