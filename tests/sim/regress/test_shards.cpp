// Shards of a regression run: the index over the count from the command line, Slurm arrays and
// Kubernetes indexed jobs, and a deterministic partition of the scenarios.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "sim/regress/shard_result.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

TEST(Shard, ParsesIndexOverCountAndRejectsNonsense) {
    EXPECT_EQ(parseShard("2/5").index, 2u);
    EXPECT_EQ(parseShard("2/5").count, 5u);
    for (const char* bad : {"5/5", "1", "a/b", "-1/3", "1/0", ""}) {
        EXPECT_THROW(parseShard(bad), std::invalid_argument) << bad;
    }
}

TEST(Shard, ReadsSlurmArraysAndKubernetesIndexedJobs) {
    std::map<std::string, std::string> env;
    auto get = [&](const char* name) -> const char* {
        const auto it = env.find(name);
        return it == env.end() ? nullptr : it->second.c_str();
    };
    EXPECT_EQ(shardFromEnvironment(get).count, 1u);
    env = {{"SLURM_ARRAY_TASK_ID", "4"},
           {"SLURM_ARRAY_TASK_COUNT", "4"},
           {"SLURM_ARRAY_TASK_MIN", "1"}};
    EXPECT_EQ(shardFromEnvironment(get).index, 3u);
    EXPECT_EQ(shardFromEnvironment(get).count, 4u);
    env = {{"JOB_COMPLETION_INDEX", "0"}, {"OCCSIM_SHARD_COUNT", "3"}};
    EXPECT_EQ(shardFromEnvironment(get).index, 0u);
    EXPECT_EQ(shardFromEnvironment(get).count, 3u);
    env = {{"JOB_COMPLETION_INDEX", "0"}};
    EXPECT_THROW(shardFromEnvironment(get), std::invalid_argument);
}

TEST(Shard, ShardsPartitionTheScenariosDeterministically) {
    const fs::path dir =
        fs::temp_directory_path() / ("occsim-regress-shards-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "nested");
    for (int i = 0; i < 7; ++i) {
        // Appended rather than "s" + ... + ".json": GCC 12 warns falsely (-Wrestrict) on that here.
        std::string name = "s";
        name += std::to_string(i);
        name += ".json";
        std::ofstream(dir / name) << "{}";
    }
    std::ofstream(dir / "nested" / "t.json") << "{}";
    std::ofstream(dir / "s0.baseline.json") << "{}";
    std::set<fs::path> all;
    size_t total = 0;
    for (uint32_t i = 0; i < 3; ++i) {
        const auto mine = collectScenarios({dir}, {i, 3});
        EXPECT_EQ(mine, collectScenarios({dir}, {i, 3}));
        total += mine.size();
        for (const ScenarioFile& s : mine) all.insert(s.file);
    }
    EXPECT_EQ(total, 8u);
    EXPECT_EQ(all.size(), 8u) << "every scenario in exactly one shard, baselines excluded";
}

}  // namespace
}  // namespace occsim
