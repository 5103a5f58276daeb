// The merge end to end on real runs: the small scenarios (a few frames each) run as four shards
// and on one machine give the same report check for check, and a run's summaries make a history
// entry with every algorithm's figures.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "sim/regress/history.h"
#include "sim/regress/merge.h"
#include "sim/regress/shard_result.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

RegressOptions shortRun(const fs::path& scenarios, const fs::path& out, Shard shard,
                        bool update = false) {
    RegressOptions o;
    o.inputs = {scenarios};
    o.shard = shard;
    o.update = update;
    o.out_dir = out;
    // Few frames, and no frame-time ratio: the checks left are counts, identical run after run in
    // deterministic-latency mode, so two runs can be compared check for check.
    o.adjust_scenario = [](Scenario& s) {
        s.expect->frames = 8;  // past every small scenario's warm-up, so speedups are timed
        s.expect->ratios.clear();
    };
    return o;
}

TEST(MergeRun, FourShardsMatchAOneMachineRunCheckForCheck) {
    const fs::path root =
        fs::temp_directory_path() / ("occsim-merge-run-" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root);
    for (const char* folder : {"small", "assets"}) {  // the small ones read glTF files from assets/
        fs::copy(fs::path(OCCSIM_SOURCE_DIR) / "scenarios" / folder, root / folder,
                 fs::copy_options::recursive);
    }
    // Baselines of the short run, so the count checks compare against something that holds.
    runRegression(shortRun(root / "small", root / "update", {}, true));

    const ScenarioSet set = scenarioSetOf({root / "small"});
    ASSERT_EQ(set.scenarios.size(), 8u);
    std::vector<fs::path> dirs;
    for (uint32_t i = 0; i < 4; ++i) {
        const RegressOptions o =
            shortRun(root / "small", root / ("shard-" + std::to_string(i)), {i, 4});
        writeShardResult(o.out_dir, {o.out_dir, set, o.shard, "host", "cpu", runRegression(o)});
        dirs.push_back(o.out_dir);
    }
    const RegressOptions single = shortRun(root / "small", root / "single", {});
    const RegressReport one = runRegression(single);
    writeShardResult(single.out_dir, {single.out_dir, set, single.shard, "host", "cpu", one});

    const MergedRun merged = mergeShards(dirs);
    const MergedRun alone = mergeShards({single.out_dir});
    EXPECT_TRUE(one.passed()) << one.table();
    EXPECT_EQ(checksTsv(merged.report), checksTsv(one));
    EXPECT_EQ(checksTsv(merged.report), checksTsv(alone.report));
    EXPECT_EQ(merged.report.table(), one.table());
    size_t checks = 0;
    for (const auto& s : merged.report.scenarios) checks += s.checks.size();
    EXPECT_GT(checks, 8u * 4u);
    EXPECT_EQ(merged.shard_of, (std::vector<uint32_t>{0, 1, 2, 3, 0, 1, 2, 3}));

    // Every scenario's summary came along, and makes a history entry.
    std::vector<std::pair<std::string, Json>> summaries;
    for (size_t k = 0; k < merged.summaries.size(); ++k) {
        ASSERT_FALSE(merged.summaries[k].is_null()) << merged.report.scenarios[k].name;
        summaries.emplace_back(merged.report.scenarios[k].name, merged.summaries[k]);
    }
    const HistoryEntry e = historyEntryNow(summaries, "test");
    EXPECT_EQ(e.scenarios.size(), 8u);
    EXPECT_FALSE(e.backend.empty());
    EXPECT_FALSE(e.renderer.empty());
    const AlgorithmFigures& f = e.scenarios.at("teapots-small").at("statistical");
    ASSERT_TRUE(f.speedup.has_value());
    EXPECT_GT(*f.speedup, 0.0);
    EXPECT_GT(f.queries, 0.0);
    EXPECT_GT(f.objects, 0.0);
    fs::remove_all(root);
}

}  // namespace
}  // namespace occsim
