#include "sim/commands/history.h"

#include <cstdio>

#include "occsim/culling/contract/input_error.h"
#include "sim/commands/flag_checks.h"
#include "sim/output/run_folder.h"
#include "sim/regress/history.h"
#include "sim/regress/history_report.h"
#include "sim/regress/result_files.h"

namespace occsim_cli {

using occsim::ResultFileError;

CLI::App* addHistory(CLI::App& app, HistoryFlags& flags) {
    CLI::App* history = app.add_subcommand("history",
                                           "Report a history folder: plots over the runs, changes "
                                           "beyond the run-to-run spread flagged");
    history->add_option("dir", flags.dir, "History folder (regress --history)")->required();
    history->add_option("--out", flags.out,
                        "Folder for report.md and the plots (default out/history)");
    history
        ->add_option("--window", flags.window,
                     "Compare the median of the last N runs with the N before (default 3)")
        ->check(integerIn(1, 1000));
    history
        ->add_option("--min-change", flags.min_change,
                     "Smallest relative change flagged, beside the spread (default 0.05)")
        ->check(CLI::Range(0.0, 10.0));
    history->add_flag("--fail-on-change", flags.fail_on_change,
                      "Exit with status 1 when a figure got worse beyond the spread");
    return history;
}

int historyCommand(const HistoryFlags& flags) {
    if (flags.out.empty())
        throw occsim::InputError("--out: empty; expected a folder (created when missing)");
    if (sameFolder(flags.dir, flags.out)) {
        throw occsim::InputError("--out " + flags.out +
                                 ": is the history folder; expected a folder of its own");
    }
    // The report's folder follows the run folder's rule (run_folder.h): replaced as a whole, and
    // only when it is empty, absent or an earlier occsim output.
    const occsim::FolderLock lock(flags.out, false);
    occsim::checkRunFolder(occsim::resolvedFolder(flags.out));
    std::vector<occsim::HistoryEntry> runs = occsim::readHistory(flags.dir);
    if (runs.empty())
        throw ResultFileError(flags.dir +
                              ": no history entries (*.json); expected at least one run");
    occsim::HistoryOptions options;
    options.window = flags.window;
    options.min_change = flags.min_change;
    const occsim::HistoryAnalysis analysis = occsim::analyseHistory(std::move(runs), options);
    occsim::StagedRunFolder folder(flags.out);
    const auto files = occsim::writeHistoryReport(folder.staging(), analysis, options);
    folder.publish();
    for (const auto& c : analysis.flagged) std::printf("changed: %s\n", c.text().c_str());
    for (const auto& s : analysis.not_compared) std::printf("not compared: %s\n", s.c_str());
    std::printf(
        "history: %zu runs, %zu series, %zu scenarios, %zu changes flagged; written %s/report.md "
        "and %zu "
        "plots\n",
        analysis.runs.size(), analysis.series.size(), analysis.scenarios.size(),
        analysis.flagged.size(), flags.out.c_str(), files.size() - 1);
    return flags.fail_on_change && !analysis.flagged.empty() ? 1 : 0;
}

}  // namespace occsim_cli
