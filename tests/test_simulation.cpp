// End to end through OSMesa: the small teapot scenario, every algorithm, ground truth and error.
#include "culling/culler_factory.h"
#include "sim/runner.h"
#include "sim/scenario.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace occsim {
namespace {

const std::filesystem::path kSmall = std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json";

std::filesystem::path freshDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("occsim-test-" + name);
    std::filesystem::remove_all(dir);
    return dir;
}

BenchResult benchSmall(const std::string& name, bool error, LatencyMode latency,
                       std::vector<std::string> algorithms = cullerNames()) {
    BenchOptions options;
    options.algorithms = std::move(algorithms);
    options.measure_error = error;
    options.latency = latency;
    options.out_dir = freshDir(name);
    return runBenchmark(parseScenarioFile(kSmall), options);
}

TEST(Simulation, ConservativeAlgorithmsAndIdealShowZeroErrorPixelsOnEveryFrame) {
    std::vector<std::string> conservative;
    for (const std::string& name : cullerNames()) {
        if (name != "async") conservative.push_back(name);  // per-object async may miss by design
    }
    const BenchResult result = benchSmall("zero-error", true, LatencyMode{}, conservative);
    ASSERT_EQ(result.runs.size(), conservative.size());
    for (const RunRecord& run : result.runs) {
        ASSERT_EQ(run.frames.size(), 40u);
        for (const FrameStats& f : run.frames) {
            EXPECT_EQ(f.error_pixels, 0) << run.summary.algorithm << " frame " << f.frame;
            EXPECT_EQ(f.missed_objects, 0) << run.summary.algorithm << " frame " << f.frame;
            EXPECT_GT(f.visible_objects, 0);
        }
    }
}

TEST(Simulation, CullersDrawFewerObjectsThanVfcAndIdealDrawsFewestWithNoQueries) {
    const BenchResult result = benchSmall("fewer", true, LatencyMode{true, 8});
    const auto& runs = result.runs;
    auto by = [&](const std::string& name) -> const RunSummary& {
        for (const RunRecord& r : runs) {
            if (r.summary.algorithm == name) return r.summary;
        }
        throw std::runtime_error("no run " + name);
    };
    EXPECT_EQ(by("vfc").queries_mean, 0.0);
    EXPECT_EQ(by("ideal").queries_mean, 0.0);
    EXPECT_GT(by("stop-and-wait").queries_mean, by("statistical").queries_mean);
    EXPECT_LT(by("statistical").objects_mean, by("vfc").objects_mean);
    EXPECT_LT(by("stop-and-wait").objects_mean, by("vfc").objects_mean);
    EXPECT_LE(by("ideal").objects_mean, by("stop-and-wait").objects_mean);
}

TEST(Simulation, MovingObjectsAreReinsertedIntoOtherNodes) {
    const BenchResult result = benchSmall("movers", false, LatencyMode{}, {"vfc"});
    uint64_t changes = 0;
    for (const FrameStats& f : result.runs[0].frames) {
        EXPECT_EQ(f.moved_objects, f.frame == 0 ? 0u : 90u);  // 20% + 10% of 300
        changes += f.node_changes;
    }
    EXPECT_GT(changes, 0u);
}

TEST(Simulation, DeterministicLatencyGivesIdenticalDecisionsOverThreeRuns) {
    std::vector<std::vector<std::pair<uint64_t, uint64_t>>> counts;
    for (int run = 0; run < 3; ++run) {
        const BenchResult r = benchSmall("determinism", false, LatencyMode{true, 6}, {"statistical"});
        counts.emplace_back();
        for (const FrameStats& f : r.runs[0].frames) counts.back().push_back({f.queries, f.objects_drawn});
    }
    EXPECT_EQ(counts[0], counts[1]);
    EXPECT_EQ(counts[0], counts[2]);
}

TEST(Simulation, WritesFramesCsvAndSummaryJsonAndCaptures) {
    BenchOptions options;
    options.algorithms = {"statistical", "vfc"};
    options.measure_error = true;
    options.out_dir = freshDir("outputs");
    options.capture_frames = {3};
    options.frames = 6;
    runBenchmark(parseScenarioFile(kSmall), options);
    std::ifstream csv(options.out_dir / "frames.csv");
    std::string line;
    int lines = 0;
    while (std::getline(csv, line)) ++lines;
    EXPECT_EQ(lines, 1 + 2 * 6);
    const auto summary = nlohmann::json::parse(std::ifstream(options.out_dir / "summary.json"));
    EXPECT_EQ(summary["algorithms"].size(), 2u);
    EXPECT_EQ(summary["algorithms"][0]["error"]["pixels_total"], 0);
    EXPECT_TRUE(summary["algorithms"][0].contains("speedup_over_vfc"));
    EXPECT_TRUE(std::filesystem::exists(options.out_dir / "frame-00003-statistical.png"));
    EXPECT_TRUE(std::filesystem::exists(options.out_dir / "frame-00003-vfc.png"));
    for (const auto& entry : std::filesystem::directory_iterator(options.out_dir)) {
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    }
}

TEST(Simulation, DescribeReportsObjectsTrianglesMoversAndTree) {
    const std::string text = describeScenario(parseScenarioFile(kSmall));
    EXPECT_NE(text.find("objects       300"), std::string::npos) << text;
    EXPECT_NE(text.find("movers        90"), std::string::npos) << text;
    EXPECT_NE(text.find("bsp "), std::string::npos) << text;
}

}  // namespace
}  // namespace occsim
