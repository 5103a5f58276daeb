// One culler's row, what a culler (built-in or plugin) fills in and hands to the registry: its
// name, its traits (conservative, issues queries, oracle), its factory and its options descriptor
// (options.h). The host's side, the registry that holds the rows and makes cullers from them, is
// registry/registry.h; a plugin reaches this header through occsim/culling/plugin.h.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "occsim/culling/contract/cost_model.h"
#include "occsim/culling/contract/culler.h"
#include "occsim/culling/contract/input_error.h"
#include "occsim/culling/declaration/options.h"

namespace occsim {

// What a factory gets: the culler's own option values (checked against its descriptor and its
// validate hook), and what drawing and querying cost here (unknown unless measured or given).
struct CullerContext {
    std::string_view name;
    const OptionValues& options;
    const CostModel& cost_model;
};

// Whether a culler configured with these options weighs costs, and how many queries it keeps in
// flight (the run layer then measures the cost model with as many in flight before the first
// frame).
struct CostModelUse {
    bool wanted = false;
    uint32_t queries_in_flight = 0;
};

struct CullerRow {
    std::string name;     // as in --algos and culling.algorithm: [a-z0-9_+-], unique
    std::string summary;  // one line, for help texts and docs
    // Never hides a visible pixel by design (with the approximation knobs off): regression runs
    // expect zero error of it unless a scenario says otherwise.
    bool conservative = true;
    // Decides with occlusion queries: the approximation knobs (pixel threshold, stale results)
    // apply to it.
    bool issues_queries = false;
    // Decides from ground truth (the Ideal oracle): needs a ground-truth render every frame, and
    // is the bound others are measured against, never a candidate on a time-against-error front.
    bool oracle = false;
    // The reference that speedups are measured against (frustum culling); exactly one built-in.
    bool speedup_reference = false;
    // The device capabilities it cannot run without (DeviceFeature bits, render_device.h): a run
    // on a device that lacks one refuses this culler before any work, naming it and the feature.
    uint32_t device_needs = 0;
    // Rasterises the scene's triangles itself: the run fills CullFrame::meshes (the flat mesh
    // arrays, built once, and every frame's object transforms) for it, and for no other culler.
    bool needs_meshes = false;
    // Its options, read from culling.<name> in a scenario.
    OptionsDescriptor options;
    std::unique_ptr<Culler> (*factory)(const CullerContext& context) = nullptr;
    // Rules that tie options together (each option's own range is the descriptor's): empty when
    // the values are fine, else one line naming the keys. nullptr: no such rules.
    std::string (*validate)(const OptionValues& values) = nullptr;
    // nullptr: never weighs costs.
    CostModelUse (*cost_model_use)(const OptionValues& values) = nullptr;
    // Where it came from: empty for a built-in, the plugin's file otherwise.
    std::string source;
};

// A registration the registry refuses: what is wrong, in one line.
struct RegistryError : InputError {
    using InputError::InputError;
};

}  // namespace occsim
