// The command line's side of merging shards and of the history (docs/regression.md): what
// `occsim regress` leaves for them, `occsim merge` and `occsim history`. Bad input (a flag, a
// shard folder, a history entry) throws occsim::ResultFileError with one line; main() prints it
// and exits with status 2, and nothing has been written by then.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/regress/regress.h"

namespace occsim_cli {

// `regress --history DIR`: refused before the run when DIR holds entries this program cannot read.
void checkHistoryFlag(const std::string& history_dir);

// After `occsim regress`: shard.json and junit.xml into the --out folder (for `occsim merge`),
// and, with --history, the run's figures as a new history entry.
void writeRegressResults(const occsim::RegressOptions& options, const occsim::RegressReport& report,
                         const std::string& history_dir, const std::string& commit);

struct MergeFlags {
    std::vector<std::string> dirs;
    std::string out = "out/merged";
    std::string junit, history, commit;
};
int mergeCommand(const MergeFlags& flags);

struct HistoryFlags {
    std::string dir;
    std::string out = "out/history";
    size_t window = 3;
    double min_change = 0.05;
    bool fail_on_change = false;
};
int historyCommand(const HistoryFlags& flags);

}  // namespace occsim_cli
