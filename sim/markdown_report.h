// report.md: one page a person can read after `occsim bench` or `occsim run`, with the
// comparison table, the plots and the bird's-eye pictures.
//
// Contract
// - markdownReport() is pure formatting: it measures nothing and touches no file. The table has
//   exactly the columns of formatComparisonTable() (comparisonTable() gives both), with the
//   Pareto configurations marked. Only the pictures named in the context are linked (by file
//   name, relative to report.md, which lives in the same folder).
// - The header states the scenario, the exact command, the machine, the warm-up frames excluded
//   from timing, and that ground-truth rendering, PNG writing and statistics I/O are outside all
//   timing.
#pragma once

#include "sim/bench_config.h"
#include "sim/runner.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace occsim {

struct ReportContext {
    std::string command_name = "bench";  // "bench" or "run"
    std::string scenario_name;
    std::string scenario_file;
    uint32_t frames = 0;
    uint32_t warmup_frames = 0;
    uint32_t repetitions = 1;
    bool error_measured = false;
    std::optional<uint32_t> deterministic_latency;  // commands, when the mode was on
    // The machine.
    uint32_t hardware_threads = 0;
    std::string lp_num_threads = "default";
    std::string renderer;
    uint32_t width = 0, height = 0;
    std::string command_line;
    std::optional<Sweep> sweep;
    // Pictures that exist in the report's folder (file names).
    std::vector<std::string> plot_files;       // PNG and SVG; the PNGs are shown
    std::vector<std::string> birds_eye_files;
    std::string plots_note;                    // why plots are missing or incomplete, if so
};

std::string markdownReport(const BenchResult& result, const ReportContext& context);

}  // namespace occsim
