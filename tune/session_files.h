// What a finished tuning session writes into its folder (occtune's command line calls this;
// the session itself, tune/tuner.h, writes only its sample log).
#pragma once

#include "sim/output/plots.h"
#include "tune/tuner.h"

namespace occsim::tune {

// cost_model.json, the charts, report.md, then tuned.json (or tuned.rejected.json, for values
// the confirmation rejected) last, so that its presence means the session finished; a rejected
// result has no tuned.json beside it, not even one left from before. Adds what it wrote to
// session.result.files (and the charts' message) for the report; returns the charts' outcome.
PlotResult writeSessionFiles(TuneSession& session);

}  // namespace occsim::tune
