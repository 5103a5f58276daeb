// Where a regression run may read and write baselines (docs/regression.md "Baselines"): each
// scenario's `expect.baseline` lies in the scenario's own folder (or below it, symlinks resolved),
// is no scenario file of the run (the scenario itself included), belongs to one scenario only,
// is no folder, and, when --update would write it, is absent or an occsim baseline of the same
// scenario already: a run never overwrites a file that is not its own, whatever else it runs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace occsim {

struct BaselinePlace {
    std::filesystem::path scenario_file;  // as found
    std::filesystem::path baseline;       // as the scenario names it (expect.baseline)
    std::string scenario_name;            // what its baseline records; empty: not checked
};

// Whether `file` holds JSON whose "format" is "occsim-baseline" (any version: an older baseline
// is still ours to rewrite).
bool isOccsimBaselineFile(const std::filesystem::path& file);

// The scenario name an occsim baseline file records ("scenario"); empty when it records none or
// is no baseline.
std::string baselineScenarioName(const std::filesystem::path& file);

// One line per problem ("<scenario>: /expect/baseline: ..."), empty when every place is good.
// `scenario_files` are every scenario file of the run, of every shard.
std::vector<std::string> baselinePlaceProblems(
    const std::vector<BaselinePlace>& places,
    const std::vector<std::filesystem::path>& scenario_files, bool update);

}  // namespace occsim
