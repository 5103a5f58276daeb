// `occsim history DIR`: the runs of a history folder (history.h) as a report, and the changes
// beyond the run-to-run spread flagged. Per series (one machine and backend: never averaged
// with another), scenario, algorithm and figure, the median of the last `window` runs is
// compared with the median of the `window` runs before them; the change is flagged when it is
// larger than the spread, the largest change between two consecutive runs before the last
// `window`, and than `min_change` of the earlier median (so that figures which never moved do
// not flag a rounding difference). A series needs window + 2 runs to be compared.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/regress/history.h"

namespace occsim {

struct HistoryOptions {
    size_t window = 3;
    double min_change = 0.05;  // relative
};

// One figure the report follows; `get` reads it from an algorithm's figures (nullopt: absent).
struct HistoryFigure {
    const char* name;  // "speedup over VFC"
    const char* key;   // "speedup", for file and column names
    bool higher_is_better;
    std::optional<double> (*get)(const AlgorithmFigures&);
};
const std::vector<HistoryFigure>& historyFigures();

struct FlaggedChange {
    std::string series, scenario, algorithm, figure;
    double before = 0, after = 0, spread = 0;
    bool worse = false;
    std::string text() const;  // one line for the report and the terminal
};

struct HistoryAnalysis {
    std::vector<HistoryEntry> runs;      // oldest first
    std::vector<std::string> series;     // in order of first appearance
    std::vector<std::string> scenarios;  // sorted
    std::vector<FlaggedChange> flagged;
    std::vector<std::string> not_compared;  // series with too few runs, said in the report

    // Whether a flagged change is worse: what `history --fail-on-change` fails on (a figure that
    // got better is flagged and printed, and exits 0).
    bool anyWorse() const;
};

HistoryAnalysis analyseHistory(std::vector<HistoryEntry> runs, const HistoryOptions& options);
std::string historyMarkdown(const HistoryAnalysis& analysis, const HistoryOptions& options);
// out/report.md and out/history-<scenario>.svg per scenario, each atomically; returns the names.
std::vector<std::string> writeHistoryReport(const std::filesystem::path& out,
                                            const HistoryAnalysis& analysis,
                                            const HistoryOptions& options);

// The median of the values (the mean of the middle two for an even count); 0 for none.
double median(std::vector<double> values);

}  // namespace occsim
