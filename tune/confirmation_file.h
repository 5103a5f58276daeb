// confirmation.json: what a finished session measured in its confirmation, as numbers, for
// scripts that tabulate many sessions (scripts/tune_table.py). report.md says the same for a
// reader; this file is its machine-readable twin and carries nothing report.md does not.
#pragma once

#include <string>

#include "tune/result.h"

namespace occsim::tune {

// The culler, the scenario, the verdict, each tuned parameter (its reference value, the value
// chosen, whether it was kept at the reference, which bound it sits on) and, per confirmation
// variant, the tuned/reference ratios (median, min, max over repetitions), times, counts and
// error.
std::string confirmationJson(const TuneResult& result);

}  // namespace occsim::tune
