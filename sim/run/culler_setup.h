// The one construction path of a configuration's culler, shared by runs, the tuner and the viewer:
// the cost model a culler that weighs costs reads (given, measured here, or the reference), then
// the culler from its registry row.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "sim/run/calibration.h"
#include "sim/run/run_config.h"
#include "sim/scenario/scenario.h"

namespace occsim {

class GlRenderer;
struct LatencyMode;
struct Scene;

// Gives every configuration whose culler weighs costs (CullerRow::cost_model_use) and has no
// cost model one: measured on this renderer before the first frame, or, when decisions must be
// reproducible (deterministic latency), the reference figures. A cost model given by the scenario
// is kept as it is; one given for a culler alone (CullerOptions::cost_model_of) goes to that culler
// only. Returns what was chosen, nullopt when no configuration weighs costs.
std::optional<CostModelChoice> chooseCostModel(std::vector<RunConfig>& configs, const Scene& scene,
                                               const Scenario& scenario, GlRenderer& renderer,
                                               const LatencyMode& latency);

// The configuration's culler (after chooseCostModel).
std::unique_ptr<Culler> makeConfiguredCuller(const RunConfig& config);

}  // namespace occsim
