// Charts of a benchmark through gnuplot, only when plots are asked for (`--plots`).
//
// Contract
// - writePlots() looks for `gnuplot` on PATH. Without it, it returns ok = false with the message
//   "plots skipped: gnuplot not found; install the Debian package gnuplot-nox" and writes nothing.
// - Otherwise it writes the data (plot-frames.dat, plot-configs.dat, plot-pareto.dat) and the
//   script (plots.gp) into out_dir, runs gnuplot there, and produces each chart as PNG (pngcairo,
//   or png where pngcairo is missing) and SVG:
//     plot-frame-time      frame time per frame, every configuration on one chart (first
//                          repetition; the warm-up frames shaded)
//     plot-time-vs-error   mean frame ms against mean error pixels per frame, one labelled point
//                          per configuration, the Pareto front (RunRecord::pareto) as a line;
//                          only when error was measured
//     plot-queries-triangles  queries per frame and triangles drawn per frame, two panels
// - gnuplot writes to temporary names that are renamed into place only after it succeeded, so a
//   picture is whole or absent. On failure no picture is left, and the message quotes gnuplot's
//   error. The data files and the script are kept either way (they are written atomically).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/output/report.h"

namespace occsim {

struct PlotResult {
    bool ok = false;
    std::string message;             // one line: what was skipped or why it failed; may be set
                                     // when ok (e.g. no time-against-error chart without error)
    std::vector<std::string> files;  // names (in out_dir) of the pictures written
};

PlotResult writePlots(const std::vector<RunRecord>& runs, const std::filesystem::path& out_dir);

// One picture for renderCharts(): gnuplot commands after the terminal and output are set.
struct GnuplotChart {
    std::string name;  // file stem
    int width = 1100, height = 600;
    std::string body;
};

// The machinery behind writePlots(), for other charts (the tuner's): writes `script_name` into
// out_dir, runs gnuplot there (found on PATH) and publishes every chart as PNG and SVG, each whole
// or absent, as above. The data files the charts read must be in out_dir already.
PlotResult renderCharts(const std::vector<GnuplotChart>& charts,
                        const std::filesystem::path& out_dir, const std::string& script_name);

// The first executable file named `program` in the directories of $PATH.
std::optional<std::filesystem::path> findOnPath(const std::string& program);

}  // namespace occsim
