// What a run configures of its cullers: each culler's option values (by culler name; a culler
// not named takes its descriptor's defaults), the cost model the cullers that weigh costs read,
// and the approximation knobs every culler that issues queries shares.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "occsim/culling/contract/cost_model.h"
#include "occsim/culling/declaration/options.h"
#include "occsim/culling/devices/approximation_options.h"

namespace occsim {

struct CullerRow;

struct CullerOptions {
    CostModel cost_model;  // unknown (all zero) unless given or measured at start-up
    // A cost model given for these cullers only (culling.cost_model with "cullers"): it replaces
    // cost_model for them and reaches no other culler (a tuned.json changes what it was tuned for).
    std::map<std::string, CostModel, std::less<>> cost_model_of;
    ApproximationOptions approximation;
    // The values given for a culler (scenario, --culling file, sweep, tuner), by culler name.
    std::map<std::string, OptionValues, std::less<>> given;

    // The culler's values: as given, or its defaults.
    OptionValues of(const CullerRow& culler) const;
    // The culler's values to change (its defaults first when none were given).
    OptionValues& edit(const CullerRow& culler);

    // The first invalid value's message, "<culler>: <key>: expected ..." (checkOptionValues).
    bool isValid(std::string* error) const;
};

}  // namespace occsim
