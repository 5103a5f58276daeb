// tuned.json: the tuned values (and the fitted cost model) in the form of a scenario's "culling"
// section, which `occsim run|bench|regress --culling tuned.json` reads with the scenario parser's
// own strict readers (sim/scenario/culling_file.h).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "occsim/culling/registry/registry.h"
#include "tune/frame_time_model.h"

namespace occsim::tune {

// The ONE place where the fitted cost model meets the option that reads it
// (`culling.cost_model`, read by the cullers that weigh costs, docs/cullers.md): {"query_box_ms",
// "triangle_ms", "draw_call_ms"}, milliseconds per query (the fit's per-query cost: one box for
// most queries), per drawn triangle and per draw call, with "cullers": [culler]: the model is for
// the tuned culler alone, so that applying the file changes no other culler that weighs costs.
// Adds nothing, and returns false, when all three are 0 (the culler would refuse it).
bool addCostOption(nlohmann::json& culling, const FrameTimeModel& model, const std::string& culler);

struct TunedFile {
    std::string text;  // the file's contents
    bool has_cost_option = false;
    bool weighs_costs = false;  // the tuned culler reads culling.cost_model
    std::string note;           // what else the file changes, when it carries a cost model
};

// Every option of the tuned culler is written, so that the file says the whole setting it was
// tuned and confirmed with. The cost model is written only when the culler, so configured, weighs
// costs (AlgorithmTraits::cost_model_use), scoped to that culler (addCostOption); `note` says so.
// Checked by reading it back through the scenario layer (as --culling does); throws
// std::runtime_error with that reader's one line when it would be refused, or when it does not read
// back as the tuned values.
TunedFile tunedFile(const AlgorithmTraits& algorithm, const OptionValues& tuned,
                    const FrameTimeModel& cost);

}  // namespace occsim::tune
