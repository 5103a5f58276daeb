// What a benchmark returns: per configuration its frames and summaries, the run's metadata (built
// once, read by the console, summary.json and report.md alike), and the worst error frames.
#pragma once

#include "culling/algorithms.h"
#include "sim/run/frame_stats.h"
#include "sim/run/run_config.h"
#include "sim/run/simulation.h"

#include <cstdint>
#include <optional>
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
    const AlgorithmTraits* algorithm = nullptr;          // the culler
    bool pareto = false;                                 // on the time-against-error front
};

// Everything about a run that is not a measurement: what ran, how, and where.
struct RunMetadata {
    std::string command = "bench";  // the command that ran it: run, bench, regress, tune
    std::string command_line;       // as typed
    // The scenario.
    std::string scenario_name;
    std::string scenario_file;
    uint32_t frames = 0;
    uint32_t warmup_frames = 0;
    double dt_s = 0.0;
    uint64_t seed = 0;
    uint32_t objects = 0;
    uint64_t triangles = 0;
    uint32_t movers = 0;
    // The run.
    uint32_t repetitions = 1;
    bool error_measured = false;
    std::optional<uint32_t> deterministic_latency;  // commands, when the mode was on
    std::optional<Sweep> sweep;
    // The cost model the cullers that weigh costs were given (statistical+), and where it came
    // from: "scenario", "calibrated" (measured before the first frame) or "reference".
    std::optional<CostModel> cost_model;
    std::string cost_model_source;
    // The machine.
    uint32_t hardware_threads = 0;
    std::string lp_num_threads = "default";  // LP_NUM_THREADS as set, or "default"
    std::string renderer;
    uint32_t width = 0, height = 0;
};

struct BenchResult {
    RunMetadata metadata;
    std::vector<RunRecord> runs;
    std::vector<ErrorFrame> worst_error_frames;  // per run, when keep_worst_error_frame
};

// Speedup over the reference (its mean / this mean) and ratio to the oracle (this mean / the
// oracle's mean); 0 when that algorithm is not among the runs.
double speedupOverReference(const std::vector<RunRecord>& runs, const RunSummary& s);
double ratioToOracle(const std::vector<RunRecord>& runs, const RunSummary& s);

// Marks RunRecord::pareto over every run that is not an oracle (the bound is no candidate).
void markParetoFront(std::vector<RunRecord>& runs);

}  // namespace occsim
