// What one `occsim regress` run leaves in its --out folder for `occsim merge`: shard.json (this
// shard's i/n, the scenario set it was cut from with the set's full list, and every scenario's
// checks) and junit.xml. The set's list is what makes a missing shard detectable: the merge
// knows every scenario that should have run, not only those that did.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sim/regress/regress.h"
#include "sim/scenario/json_reader.h"

namespace occsim {

struct ScenarioSet {
    std::string id;                      // hash of the sorted paths and their files' contents
    std::vector<std::string> scenarios;  // every scenario file of the set, sorted
    std::vector<std::string> ids;        // per scenario file, its identity (scenario_identity.h)
};

struct ShardResult {
    static constexpr int kFormatVersion = 2;  // 2: scenario ids, the machine
    std::filesystem::path dir;                // where it was read from
    ScenarioSet set;
    Shard shard;
    std::string hostname, cpu;  // the machine it ran on
    RegressReport report;       // this shard's scenarios, in run order
};

// The set the inputs name (collectScenarios() with no sharding); the id changes when a scenario
// is added, removed, renamed or edited, so shards of different checkouts do not merge.
ScenarioSet scenarioSetOf(const std::vector<std::filesystem::path>& inputs);

std::string shardResultJson(const ShardResult& result);
// Writes dir/shard.json and dir/junit.xml (each atomically).
void writeShardResult(const std::filesystem::path& dir, const ShardResult& result);
// Reads dir/shard.json and checks dir/junit.xml against it (same suites, same counts). Throws
// ResultFileError naming the file.
ShardResult readShardResult(const std::filesystem::path& dir);

// The scenario's summary.json in a regress --out folder (dir/<id>/summary.json, as
// runRegression writes it), or null when the scenario did not run (skipped, or its file did not
// parse). Throws ResultFileError when it ran and its summary is missing, unreadable, or belongs
// to another scenario (its "scenario" block names another id, name or file).
Json scenarioSummary(const std::filesystem::path& dir, const ScenarioOutcome& outcome);

}  // namespace occsim
