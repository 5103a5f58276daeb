// The choice of a session: the fitted response's minimum within the search box (exact:
// minimiseOverBox), with the parameters the response model dropped kept at the reference values,
// and which chosen values sit on a bound of the box (what boundWarnings() in report.h says).
#pragma once

#include "tune/parameters.h"
#include "tune/result.h"

namespace occsim::tune {

// Fills r.tuned_unit, r.tuned_values, r.kept_at_paper, r.bounds_hit and the predictions from
// r.response and r.dropped. A kept parameter takes the reference value even when --bounds
// excludes it (report.h: boundWarnings() says so); a tuned one always lies within its bounds.
void chooseTunedValues(TuneResult& r, const ParameterSpace& space);

}  // namespace occsim::tune
