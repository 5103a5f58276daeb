// What occtune says at the end of a session: on stderr when it was interrupted or a fit did not
// converge (one line each), on stdout the choice, both models, the confirmation and the verdict.
#pragma once

#include <string>

#include "sim/output/plots.h"
#include "tune/tuner.h"

namespace occsim::tune {

// The line that says where the samples are and how to resume (command_line: as typed).
void printInterrupted(const TuneSession& session, const TuneOptions& options);

void printFitFailed(const TuneSession& session);

// After writeSessionFiles(): `charts` is its outcome (a message when they could not be drawn).
void printFinished(const TuneSession& session, const PlotResult& charts);

}  // namespace occsim::tune
