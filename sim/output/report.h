// Turning per-frame figures into what a person reads: the comparison table, frames.csv and
// summary.json. Formatting only; nothing here measures anything or touches a file.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/run/pixel_error.h"
#include "sim/run/results.h"

namespace occsim {

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

// One configuration's entry of summary.json's "algorithms": its figures, options and, where they
// mean something, its speedup over VFC and ratio to Ideal among `runs`.
nlohmann::json configurationJson(const RunRecord& r, const std::vector<RunRecord>& runs);

// summary.json: the metadata (scenario, machine, command) and every configuration's figures.
nlohmann::json summaryJson(const BenchResult& result);

// What the run cost beside its frames, in one line for the console and report.md: the wall clock
// of the frame loops against the sum of the frame times, the shared world's update, and ground
// truth (renders and their time, or that none was rendered).
std::string costsLine(const BenchResult& result);
// How repetitions were joined (medians of times, sums of error counts) and what decided the
// Pareto mark; empty when there is nothing to say (one repetition, no error measured).
std::string aggregationLine(const BenchResult& result);

// The console's header: "<scenario>: N frames (M timed after W warm-up), <renderer>", the
// machine's hardware threads and load average before and after the run, and a line saying so
// when the machine was busier than its hardware threads.
std::string runHeadline(const BenchResult& result);

}  // namespace occsim
