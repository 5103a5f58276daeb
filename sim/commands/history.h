// `occsim history`: a history folder (regress --history) reported, plots over the runs and the
// changes beyond the run-to-run spread flagged (docs/regression.md). Bad input (a flag, an entry
// this program cannot read) throws occsim::ResultFileError, an InputError, before anything is
// written.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

namespace occsim_cli {

struct HistoryFlags {
    std::string dir;
    std::string out = "out/history";
    size_t window = 3;
    double min_change = 0.05;
    bool fail_on_change = false;
};

CLI::App* addHistory(CLI::App& app, HistoryFlags& flags);

// Returns the exit code: 1 with --fail-on-change when a figure got worse beyond the spread.
int historyCommand(const HistoryFlags& flags);

}  // namespace occsim_cli
