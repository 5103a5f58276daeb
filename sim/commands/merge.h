// `occsim merge`: the --out folders of the shards of one regress run joined into one report,
// checking that every scenario ran exactly once (docs/regression.md). Bad input (a flag, a shard
// folder) throws occsim::ResultFileError, an InputError, before anything is written.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace occsim_cli {

struct MergeFlags {
    std::vector<std::string> dirs;
    std::string out = "out/merged";
    std::string junit, history, commit;
};

CLI::App* addMerge(CLI::App& app, MergeFlags& flags);

// Returns the exit code: 0 every check of every shard passed, 1 otherwise.
int mergeCommand(const MergeFlags& flags);

}  // namespace occsim_cli
