// The simulator's commands as functions: run/bench one scenario with one or more algorithms
// (interleaved frame by frame), and describe what a scenario builds without rendering.
#pragma once

#include "culling/culler_factory.h"
#include "sim/bench_config.h"
#include "sim/report.h"
#include "sim/simulation.h"
#include "sim/scenario.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace occsim {

struct BenchOptions {
    std::vector<std::string> algorithms;  // names from cullerNames(); validated by the caller
    bool measure_error = false;
    LatencyMode latency;
    std::optional<uint32_t> frames;       // overrides the scenario's frame count
    std::vector<uint32_t> capture_frames; // frames whose culled colour buffer is saved as PNG
    std::filesystem::path out_dir;        // where frames.csv, summary.json and captures go
    std::string command_line;             // recorded in summary.json
    bool progress = false;                // a progress line on stderr
    bool keep_worst_error_frame = false;  // see SimulationOptions; needs measure_error
    uint32_t repetitions = 1;             // each configuration runs this often; medians reported
    std::optional<Sweep> sweep;           // one configuration per value (bench_config.h)
    // Makes the culler for a name; default makeCuller(). Tests inject deliberately broken ones.
    std::function<std::unique_ptr<Culler>(const std::string&, const CullerOptions&)> make_culler;
};

struct BenchResult {
    std::vector<RunRecord> runs;
    std::vector<ErrorFrame> worst_error_frames;  // per run, when keep_worst_error_frame
    uint32_t width = 0, height = 0;
    std::string renderer;
    std::string table;
};

// Throws std::runtime_error on rendering or output failures.
BenchResult runBenchmark(const Scenario& scenario, const BenchOptions& options);

// What `occsim info` prints: objects, triangles, movers, BSP depth, nodes, objects per leaf,
// scene bounds. Builds the scene and the tree; renders nothing.
std::string describeScenario(const Scenario& scenario);

}  // namespace occsim
