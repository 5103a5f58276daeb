// `occsim regress`: every scenario with an expect block under the paths given, run and checked
// against its baseline (docs/regression.md); the checks' table on stdout, JUnit XML, the shard's
// results for `occsim merge` and, with --history, a history entry.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "sim/commands/shared_flags.h"

namespace occsim_cli {

struct RegressFlags {
    std::vector<std::string> inputs;
    bool update = false, allow_empty = false, wait_lock = false, exit_zero_on_failed_checks = false;
    std::string junit, shard, out = "out/regress", culling_file;
    bool junit_given = false;  // --junit on the command line (an empty one is refused)
    std::vector<std::string> plugins;
    BackendFlags backend;
    std::string history, commit;
    bool quiet = false;               // no progress on stderr
    std::vector<std::string> record;  // --record: "objects"
};

CLI::App* addRegress(CLI::App& app, RegressFlags& flags);

// Returns the exit code: 0 every check passed, 1 one failed (or nothing was checked).
int regressCommand(const RegressFlags& flags);

}  // namespace occsim_cli
