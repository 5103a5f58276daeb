// The history of regression runs: one file per run in a history folder (`occsim regress
// --history DIR`, `occsim merge ... --history DIR`), with the run's commit, date, machine and
// backend and, per scenario and algorithm, the figures that tell whether culling got slower:
// speedup over VFC, queries, objects drawn and error pixels per frame. `occsim history DIR`
// reads them back (history_report.h). Runs from different machines or backends are different
// series; nothing here mixes them.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/scenario/json_reader.h"

namespace occsim {

struct AlgorithmFigures {
    std::optional<double> speedup;  // over VFC in the same run; absent when VFC did not run
    double queries = 0;             // per frame, mean
    double objects = 0;             // drawn per frame, mean
    double error = 0;               // error pixels per frame, mean
};

struct HistoryEntry {
    static constexpr int kFormatVersion = 1;
    std::string file;          // its name in the history folder (set when read)
    std::string commit, date;  // date: UTC, ISO 8601 ("2025-01-31T12:00:00Z")
    std::string hostname, cpu, renderer, backend;
    // scenario -> algorithm -> figures
    std::map<std::string, std::map<std::string, AlgorithmFigures>> scenarios;

    // What tells series apart: machine (host, CPU, renderer) and backend.
    std::string series() const;
};

// This machine as a history series names it: its host name and CPU model ("unknown" when not
// found).
std::string thisHostName();
std::string thisCpuModel();

// An entry for a run made now on this machine, from each scenario's summary.json (as `occsim
// regress` writes it into its --out folder): (scenario name, summary). The commit is `commit`
// when given, else $OCCSIM_COMMIT, $GITHUB_SHA or $CI_COMMIT_SHA, else `git rev-parse HEAD` in
// the working directory, else "unknown".
HistoryEntry historyEntryNow(const std::vector<std::pair<std::string, Json>>& summaries,
                             const std::string& commit);

std::string historyEntryJson(const HistoryEntry& entry);
// Throws ResultFileError naming the file (another format version included).
HistoryEntry readHistoryEntry(const std::filesystem::path& file);
// Every *.json in the folder, oldest first (by date, then file name). Throws ResultFileError when
// the folder is missing or any entry is unreadable.
std::vector<HistoryEntry> readHistory(const std::filesystem::path& dir);
// Refuses (ResultFileError) a folder holding an entry it cannot read, before anything is written.
void checkHistoryFolder(const std::filesystem::path& dir);
// Writes the entry as a new file (never over another) and returns its path.
std::filesystem::path appendHistory(const std::filesystem::path& dir, const HistoryEntry& entry);

}  // namespace occsim
