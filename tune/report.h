// report.md of a tuning session: the choice, the confirmation table, the fit quality of both
// models, every sample, and the charts. Formatting only.
#pragma once

#include <string>
#include <vector>

#include "tune/result.h"

namespace occsim::tune {

std::string reportMarkdown(const TuneResult& result);

// The confirmation as a plain-text table for the console.
std::string confirmationTable(const TuneResult& result);

// What the held-out variant is in this scene: "held out: seed 2 changes the layout of the scene
// and the movers' starts and motions; the camera path stays: ...", or, where the seed changes
// nothing (a glTF level as its file lays it, no seeded mover), that its run repeats the fitted
// frames.
std::string heldOutLine(const TuneResult& result);

// "busy machine: 2 of 9 runs of this session ran beside other work (...); these timings are not
// results", as bench says it of one run; empty when no run was busy.
std::string busyMachineNote(const TuneResult& result);

// One line per tuned parameter whose chosen value sits on a bound of its search range, with the
// --bounds that widens it (on two of the three scenes tuned first, BASE_TIME went to its lower
// bound).
std::vector<std::string> boundWarnings(const TuneResult& result);

// Whether the confirmation ran with the fitted cost model, and why not when the culler weighs
// costs (TuneResult::cost_model_applied, cost_model_note); one line.
std::string costModelLine(const TuneResult& result);

// "1.03 [0.98-1.07]"
std::string formatSpread(const Spread& s);

}  // namespace occsim::tune
