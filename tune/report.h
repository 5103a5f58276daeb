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
