// report.md: one page a person can read after `occsim bench` or `occsim run`, with the
// comparison table, the plots and the bird's-eye pictures.
//
// Contract
// - markdownReport() is pure formatting: it measures nothing and touches no file. The table has
//   exactly the columns of formatComparisonTable() (comparisonTable() gives both), with the
//   Pareto configurations marked; each segment's table follows ("Segments", the same columns
//   over its frames), then each configuration's worst windows ("Worst windows", moments.h).
//   Only the pictures named in ReportFiles are linked (by file name, relative to report.md,
//   which lives in the same folder).
// - The header states, from the run's metadata, the scenario, the exact command, the machine,
//   the warm-up frames excluded from timing, and that ground-truth rendering, PNG writing and
//   statistics I/O are outside all timing.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sim/output/object_highlights.h"
#include "sim/run/results.h"

namespace occsim {

// Pictures that exist in the report's folder (file names).
struct ReportFiles {
    std::vector<std::string> plot_files;  // PNG and SVG; the PNGs are shown
    std::vector<std::string> birds_eye_files;
    // Worst windows' worst frames (windowPictureName()), linked under "Worst windows".
    std::vector<std::string> window_pictures;
    std::string plots_note;      // why plots are missing or incomplete, if so
    std::string extra_markdown;  // a whole section, after the table (regress: the checks)
    // The objects section, when the run recorded objects.sqlite (`--record objects`).
    std::optional<ObjectHighlights> objects;
};

std::string markdownReport(const BenchResult& result, const ReportFiles& files);

}  // namespace occsim
