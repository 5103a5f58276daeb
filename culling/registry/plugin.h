// The one header a plugin culler needs beyond the culler contract: a shared object that defines
// the entry point below can be loaded with `occsim run|bench|regress|view --plugin FILE` (or a
// scenario's "plugins" key), and its cullers then run wherever the built-ins run.
//
//   #include <occsim/culling/registry/plugin.h>
//
//   static void registerMine(occsim::PluginRegistrar& registrar) {
//       occsim::AlgorithmTraits t;
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

#include "occsim/culling/registry/registry.h"

#define OCCSIM_PLUGIN_ABI_VERSION 2u

namespace occsim {

// Hands a plugin's rows to the registry; add() throws RegistryError for a row it refuses.
class PluginRegistrar {
  public:
    virtual ~PluginRegistrar() = default;
    virtual void add(AlgorithmTraits traits) = 0;
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
