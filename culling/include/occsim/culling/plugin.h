// The one header a plugin culler includes: what a culler is (the contract, the geometry, the BSP
// tree's read API and its traversal helpers, per-node state), what its registry row is (traits,
// options descriptor, option tables) and the entry point below. A shared object that defines the
// entry point can be loaded with `occsim run|bench|regress|view --plugin FILE` (or a scenario's
// "plugins" key), and its cullers then run wherever the built-ins run. The host's side of the
// registry (the registry itself, lookups, makeCuller, the plugin loader: registry/) is not here:
// a plugin hands its rows to the PluginRegistrar and never reaches the registry.
//
//   #include <occsim/culling/plugin.h>
//
//   static void registerMine(occsim::PluginRegistrar& registrar) {
//       occsim::CullerRow t;
//       t.name = "my-culler";
//       ...
//       registrar.add(std::move(t));
//   }
//   OCCSIM_PLUGIN("my plugin", registerMine)
//
// The entry point is extern "C" and carries OCCSIM_PLUGIN_ABI_VERSION, the version of every type a
// plugin shares with occsim (the culler contract, the tree, the registry's rows): a plugin built
// against other headers is refused with a message instead of crashing. Build the plugin with the
// same compiler and standard library as occsim (its types cross the boundary as C++ types).
#pragma once

#include <cstdint>

#include "occsim/culling/contract/cost_model.h"
#include "occsim/culling/contract/culler.h"
#include "occsim/culling/contract/decision_log.h"
#include "occsim/culling/contract/render_device.h"
#include "occsim/culling/declaration/culler_row.h"
#include "occsim/culling/declaration/option_table.h"
#include "occsim/culling/declaration/options.h"
#include "occsim/culling/geometry/aabb.h"
#include "occsim/culling/geometry/frustum.h"
#include "occsim/culling/geometry/query_box.h"
#include "occsim/culling/geometry/random.h"
#include "occsim/culling/tree/bsp_tree.h"
#include "occsim/culling/tree/decision_resolution.h"
#include "occsim/culling/tree/node_state.h"
#include "occsim/culling/tree/traversal.h"

// 3: this header (the registry's row apart from the registry, the tree no longer reached through
// the culler contract), CullView's view-projection and viewport, CullerRow::device_needs.
// 4: the decision log (CullFrame::decisions, PreparedView::decisions, contract/decision_log.h)
// and DepthPyramid::levelOf.
// 5: one word per thing: the row is CullerRow (was AlgorithmTraits) in
// occsim/culling/declaration/culler_row.h (was registration/algorithm_traits.h); Culler::name()
// is gone (the registry's row names a culler; nothing read it).
// 6: OptionSpec::scope (what an option acts on), and resolveDecisions' deciding subjects.
// 7: GPU-driven draws (contract/gpu_driven_draws.h, RenderDevice::gpuDrivenDraws, the DeviceFeature
// bits kGpuDrivenDraws and kBoxRaster, DeviceCounters::read_backs), Culler::afterFrame, the
// box-raster reasons of the decision log.
// 8: CullView::kind (ViewKind): a frame culls several views (a light's, two eyes), each with a
// culler instance of its own.
#define OCCSIM_PLUGIN_ABI_VERSION 8u

namespace occsim {

// Hands a plugin's rows to the registry; add() throws RegistryError for a row it refuses.
class PluginRegistrar {
  public:
    virtual ~PluginRegistrar() = default;
    virtual void add(CullerRow traits) = 0;
};

}  // namespace occsim

extern "C" {

struct OccsimPlugin {
    uint32_t abi_version;  // OCCSIM_PLUGIN_ABI_VERSION of the headers the plugin was built with
    const char* name;      // for messages
    void (*register_cullers)(occsim::PluginRegistrar& registrar);
};

// The entry point's name, for the loader.
#define OCCSIM_PLUGIN_ENTRY_POINT "occsim_plugin"

}  // extern "C"

// Defines the entry point: `OCCSIM_PLUGIN("name", function)` at namespace scope, once per plugin.
#define OCCSIM_PLUGIN(plugin_name, register_function)                                       \
    extern "C" __attribute__((visibility("default"))) const OccsimPlugin* occsim_plugin() { \
        static const OccsimPlugin plugin{OCCSIM_PLUGIN_ABI_VERSION, plugin_name,            \
                                         register_function};                                \
        return &plugin;                                                                     \
    }
