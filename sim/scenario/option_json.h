// A culler's option values in JSON, both ways, in one place: summary.json and tuned.json write
// them, the scenario parser (culling.<name>, --culling files) reads them. A boolean option is a
// JSON boolean, an integer option a JSON integer, a number option a JSON number; a value read is
// checked against its descriptor row (checkOptionValue), so that a message reads the same
// wherever the value came from.
#pragma once

#include <nlohmann/json.hpp>

#include "occsim/culling/declaration/options.h"
#include "sim/scenario/json_reader.h"

namespace occsim {

// Every option of `values` by key, in its descriptor's order and JSON type (an empty object for
// a culler without options).
nlohmann::ordered_json optionValuesJson(const OptionValues& values);

// The value `value` holds for the option `spec`, as OptionValues holds it (a boolean as 0 or 1);
// a ScenarioError at its JSON pointer when it is of the wrong type or outside the option's range.
double readOptionValue(const JsonValueReader& value, const OptionSpec& spec);

}  // namespace occsim
