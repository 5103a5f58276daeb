// tuned.json: the setting the confirmation measured and accepted (the tuned options, and the
// fitted cost model when the confirmation ran with it), in the form of a scenario's "culling"
// section, which `occsim run|bench|regress --culling tuned.json` reads with the scenario parser's
// own strict readers (sim/scenario/culling_file.h).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "occsim/culling/registry/registry.h"
#include "tune/confirm.h"
#include "tune/frame_time_model.h"
#include "tune/measure.h"

namespace occsim::tune {

// A fitted cost model is applied (in the confirmation, then in tuned.json) only when its residual
// RMS is at most this share of the mean frame time: a model that explains frames worse than that
// would steer the culler by noise (docs/tuning.md, "The cost model").
constexpr double kMaxCostModelResidualShare = 0.25;

// The ONE place where the fitted cost model meets the cost model the cullers read
// (`culling.cost_model`, docs/cullers.md): query_box_ms is the fit's per-query cost (one box for
// most queries), triangle_ms its per-triangle cost, draw_call_ms its per-draw-call cost. None when
// all three are 0 (the culler would refuse it).
std::optional<CostModel> costModelOf(const FrameTimeModel& model);

// The cost model as tuned.json carries it: {"query_box_ms", "triangle_ms", "draw_call_ms"} with
// "cullers": [culler], so that applying the file changes no other culler that weighs costs.
void addCostOption(nlohmann::json& culling, const CostModel& model, const std::string& culler);

// The tuned setting the confirmation runs: the tuned options, with the fitted cost model for the
// culler alone when it was asked for (`apply_cost_model`, occtune --apply-cost-model), the culler,
// so configured, weighs costs (CullerRow::cost_model_use), the fit converged, its residual
// RMS is at most kMaxCostModelResidualShare of the mean frame, and it has a figure > 0. `why` says,
// in one line, why a culler that weighs costs runs without it (empty otherwise).
Setting tunedSetting(const CullerRow& algorithm, const OptionValues& tuned,
                     const FrameTimeModelFit& cost, bool apply_cost_model, std::string* why);

// What tuned.json holds for a verdict: "no change" writes the reference setting (it changes no
// decision), the others the tuned setting as confirmed.
const Setting& writtenSetting(const Verdict& verdict, const Setting& tuned,
                              const Setting& reference);

struct TunedFile {
    std::string text;  // the file's contents
    bool has_cost_option = false;
    std::string note;  // what else the file changes, when it carries a cost model
};

// Every option of the tuned culler is written, so that the file says the whole setting it was
// tuned and confirmed with, and the setting's cost model when it has one, scoped to that culler
// (addCostOption); `note` says so. Checked by reading it back through the scenario layer (as
// --culling does); throws std::runtime_error with that reader's one line when it would be refused,
// or when it does not read back as the setting.
TunedFile tunedFile(const CullerRow& algorithm, const Setting& setting);

}  // namespace occsim::tune
