// One SVG picture per scenario of a history report: a panel per figure (speedup over VFC,
// queries, objects, error pixels per frame) over the runs, one line per algorithm and series
// (a series is a machine and backend: each gets its own dash pattern, and lines never join
// runs of different series), flagged changes ringed in red. Written directly as SVG so that the
// report needs no plotting program.
#pragma once

#include <string>

#include "sim/regress/history_report.h"

namespace occsim {

std::string historySvg(const HistoryAnalysis& analysis, const std::string& scenario);

}  // namespace occsim
