// Turning per-frame figures into what a person reads: the comparison table, frames.csv and
// summary.json. Formatting only; nothing here measures anything.
#pragma once

#include "sim/frame_stats.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace occsim {

// One configuration's runs. summary.algorithm holds the configuration's label (the algorithm
// name, or "name knob=value" in a sweep); with repetitions, summary is the median over them.
struct RunRecord {
    RunSummary summary;
    std::vector<FrameStats> frames;                      // first repetition
    std::vector<std::vector<FrameStats>> later_repetitions;
    std::vector<RunSummary> repetitions;                 // one per repetition
    std::string algorithm;                               // the culler
    bool pareto = false;                                 // on the time-against-error front
};

// The cells of the benchmark table: one row per configuration, with speedup over VFC and ratio
// to Ideal when those algorithms are among the records. The error columns and the "pareto"
// column ("*" on the front) appear only when error was measured.
struct ComparisonTable {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};
ComparisonTable comparisonTable(const std::vector<RunRecord>& runs);

// That table as plain text, aligned.
std::string formatComparisonTable(const std::vector<RunRecord>& runs);

// CSV with a header, one row per frame per algorithm.
std::string framesCsv(const std::vector<RunRecord>& runs);

nlohmann::json summaryJson(const std::vector<RunRecord>& runs);

// Speedup over VFC (VFC mean / this mean) and ratio to Ideal (this mean / Ideal mean); 0 when
// the reference is not among the runs.
double speedupOverVfc(const std::vector<RunRecord>& runs, const RunSummary& s);
double ratioToIdeal(const std::vector<RunRecord>& runs, const RunSummary& s);

}  // namespace occsim
