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
    bool plots = false;                   // gnuplot charts (sim/plots.h), when gnuplot is there
    // Render a bird's-eye picture of this frame's culling decisions for every configuration
    // (first repetition): birds-eye-<config>-frame-NNNNN.png.
    std::optional<uint32_t> birds_eye_frame;
    // Makes the culler for a name; default makeCuller(). Tests inject deliberately broken ones.
    std::function<std::unique_ptr<Culler>(const std::string&, const CullerOptions&)> make_culler;
};

struct BenchResult {
    std::vector<RunRecord> runs;
    std::vector<ErrorFrame> worst_error_frames;  // per run, when keep_worst_error_frame
    uint32_t width = 0, height = 0;
    std::string renderer;
    std::string table;
    std::vector<std::string> outputs;  // files written besides frames.csv and summary.json
    std::string plots_message;         // why plots were skipped or failed, or a remark
};

// Writes frames.csv, summary.json and report.md (sim/markdown_report.h) to options.out_dir, plus
// the plots and bird's-eye pictures asked for. Throws std::runtime_error on rendering or output
// failures (a failing gnuplot is reported in plots_message, not thrown).
BenchResult runBenchmark(const Scenario& scenario, const BenchOptions& options);

// What `occsim info` prints: objects, triangles, movers, BSP depth, nodes, objects per leaf,
// scene bounds. Builds the scene and the tree; renders nothing.
std::string describeScenario(const Scenario& scenario);

}  // namespace occsim
