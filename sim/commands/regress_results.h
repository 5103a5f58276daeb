// What `occsim regress` leaves for the commands after it (docs/regression.md): its shard's
// results (shard.json and junit.xml in the --out folder, for `occsim merge`) and, with --history,
// the run's figures as a new history entry (for `occsim history`). Bad input (a history folder
// this program cannot read) throws occsim::ResultFileError, an InputError, before the run.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sim/regress/regress.h"
#include "sim/regress/shard_result.h"

namespace occsim_cli {

// `regress --history DIR`: refused before the run when DIR holds entries this program cannot read.
void checkHistoryFlag(const std::string& history_dir);

// After `occsim regress`: shard.json and junit.xml into the --out folder (for `occsim merge`),
// and, with --history, the run's figures as a new history entry.
void writeRegressResults(const occsim::RegressOptions& options, const occsim::RegressReport& report,
                         const std::string& history_dir, const std::string& commit);

// The scenarios' summaries (by scenario id) appended to the history folder as one entry, and a
// line saying so. `hosts` and `cpu`, when given, are where a merged run's shards ran (the entry's
// machine); otherwise the entry names this machine.
void appendHistoryAndSay(const std::string& history_dir,
                         const std::vector<std::pair<std::string, occsim::Json>>& summaries,
                         const std::string& commit, const std::vector<std::string>& hosts = {},
                         const std::string& cpu = {});

}  // namespace occsim_cli
