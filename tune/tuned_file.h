// tuned.json: the tuned values (and the fitted cost model) in the form of a scenario's "culling"
// section, which `occsim run|bench|regress --culling tuned.json` reads with the scenario parser's
// own strict readers (sim/scenario/culling_file.h).
#pragma once

#include "culling/culler_options.h"
#include "tune/cost_model.h"

#include <nlohmann/json.hpp>

#include <string>

namespace occsim::tune {

// The ONE place where the fitted cost model meets the culler option that reads it (the cost
// option of `statistical+`, designed alongside the tuner): culling["statistical+"].cost =
// {"query_ms", "triangle_ms", "draw_ms"}, milliseconds per query box, per drawn triangle and per
// draw call. Adds nothing, and returns false, when this build has no such culler.
bool addCostOption(nlohmann::json& culling, const CostModel& model);

struct TunedFile {
    std::string text;            // the file's contents
    bool has_cost_option = false;
};

// Every StatisticalOptions key is written, so that the file says the whole setting it was tuned
// and confirmed with. Checked by reading it back through the scenario layer (as --culling does);
// throws std::runtime_error with that reader's one line when it would be refused.
TunedFile tunedFile(const StatisticalOptions& tuned, const CostModel& cost);

}  // namespace occsim::tune
