// The open registry of cullers. Each culler registers one row: its name, its traits (conservative,
// issues queries, oracle), its factory and its options descriptor (options.h). Built-in cullers
// register the same way as a plugin's (builtin_cullers.cpp: one line each), so everything that
// lists, builds, sweeps or tunes cullers (the scenario parser, `occsim bench`, the viewer, occtune,
// the docs' tables) reads this registry and nothing else.
#pragma once

#include <deque>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "occsim/culling/contract/cost_model.h"
#include "occsim/culling/contract/culler.h"
#include "occsim/culling/contract/input_error.h"
#include "occsim/culling/registry/culler_options.h"
#include "occsim/culling/registry/options.h"

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

struct AlgorithmTraits {
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

// Empty when `values` (of `culler`'s descriptor) are valid: each in its range, then the validate
// hook. Else "<key>: expected ..., got ..." or the hook's line.
std::string checkOptionValues(const AlgorithmTraits& culler, const OptionValues& values);

// The names of the DeviceFeature bits in `features`, comma separated ("conditional rendering").
std::string deviceFeatureNames(uint32_t features);
// Throws RegistryError when `culler` needs a capability (device_needs) that a device with
// `available` features lacks: "culler 'NAME' needs FEATURE, which this device does not offer".
void requireDeviceFeatures(const AlgorithmTraits& culler, uint32_t available);

class CullerRegistry {
  public:
    // Checks the row (name, traits, descriptor, factory) and adds it after the others. Throws
    // RegistryError: a name already taken, an invalid name or descriptor, no factory, a second
    // speedup reference, an oracle that claims to issue queries.
    const AlgorithmTraits& add(AlgorithmTraits traits);
    // The checks of add(), without adding: throws what add() would.
    void check(const AlgorithmTraits& traits) const;

    // In registration order: built-ins first, in the order tables list them, then plugins'.
    const std::vector<const AlgorithmTraits*>& all() const { return order_; }
    const AlgorithmTraits* find(std::string_view name) const;

  private:
    std::deque<AlgorithmTraits> rows_;  // a deque: pointers stay valid as rows are added
    std::vector<const AlgorithmTraits*> order_;
};

// The program's registry, with the built-in cullers registered on first use.
CullerRegistry& cullerRegistry();

// Shorthands over cullerRegistry().
const std::vector<const AlgorithmTraits*>& algorithms();
std::vector<std::string> algorithmNames();
const AlgorithmTraits* findAlgorithm(std::string_view name);  // nullptr when unknown
const AlgorithmTraits& speedupReference();                    // frustum culling
std::string algorithmNameList();                              // "vfc, stop-and-wait, ..."

// The culler, made by its factory from its own values in `options`. A plugin's factory that
// throws is reported as a RegistryError naming the plugin's file and the culler.
std::unique_ptr<Culler> makeCuller(const AlgorithmTraits& algorithm, const CullerOptions& options);
// The factory called with every failure (an exception, no culler) turned into a RegistryError
// "culler 'NAME': its factory ...": what makeCuller reports for a plugin, and what the plugin
// loader checks each row's defaults with.
std::unique_ptr<Culler> makeCheckedCuller(const AlgorithmTraits& algorithm,
                                          const OptionValues& values, const CostModel& costs);

}  // namespace occsim
