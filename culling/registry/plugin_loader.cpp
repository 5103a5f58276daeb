#include "occsim/culling/registry/plugin_loader.h"

#include <dlfcn.h>

#include <map>
#include <set>
#include <system_error>

#include "occsim/culling/plugin.h"
#include "occsim/culling/registry/registry.h"

namespace occsim {
namespace {

// Collects a plugin's rows, so that they are checked together before any is registered.
class CollectingRegistrar final : public PluginRegistrar {
  public:
    void add(CullerRow traits) override { rows.push_back(std::move(traits)); }
    std::vector<CullerRow> rows;
};

// The files each registry has loaded (tests use registries of their own).
std::set<std::string>& loadedFiles(const CullerRegistry& registry) {
    static std::map<const CullerRegistry*, std::set<std::string>> files;
    return files[&registry];
}

}  // namespace

std::vector<std::string> loadPlugin(const std::filesystem::path& file, CullerRegistry& registry) {
    const std::string name = file.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
        throw PluginError(name + ": no such file; expected a plugin culler (a shared object, .so)");
    }
    const std::string canonical = std::filesystem::canonical(file, ec).string();
    if (loadedFiles(registry).count(canonical)) return {};

    // RTLD_LOCAL: a plugin's symbols do not leak into the next plugin's. Never closed: its
    // cullers' code and rows live until the program ends.
    void* handle = ::dlopen(canonical.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = ::dlerror();
        throw PluginError(name + ": not a loadable shared object (" +
                          (why ? why : "dlopen failed") + ")");
    }
    using Entry = const OccsimPlugin* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(handle, OCCSIM_PLUGIN_ENTRY_POINT));
    if (!entry) {
        throw PluginError(name + ": no entry point '" OCCSIM_PLUGIN_ENTRY_POINT
                                 "'; expected a plugin built with OCCSIM_PLUGIN(...) "
                                 "(occsim/culling/plugin.h)");
    }
    const OccsimPlugin* plugin = entry();
    if (!plugin || !plugin->register_cullers) {
        throw PluginError(name + ": its entry point returned no plugin description");
    }
    if (plugin->abi_version != OCCSIM_PLUGIN_ABI_VERSION) {
        throw PluginError(name + ": built for plugin ABI version " +
                          std::to_string(plugin->abi_version) + "; this occsim loads version " +
                          std::to_string(OCCSIM_PLUGIN_ABI_VERSION) +
                          " (rebuild it against this occsim's headers)");
    }

    CollectingRegistrar registrar;
    std::vector<std::string> names;
    try {
        plugin->register_cullers(registrar);
        if (registrar.rows.empty()) throw RegistryError("it registers no culler");
        for (size_t i = 0; i < registrar.rows.size(); ++i) {
            CullerRow& row = registrar.rows[i];
            row.source = name;
            if (row.speedup_reference) {
                throw RegistryError("culler '" + row.name +
                                    "': only the built-in frustum culler is the speedup reference");
            }
            registry.check(row);
            for (size_t j = 0; j < i; ++j) {
                if (registrar.rows[j].name == row.name) {
                    throw RegistryError("culler '" + row.name + "': registered twice");
                }
            }
            // Made once from its defaults, the cost model unknown: a factory that throws or
            // makes nothing fails now rather than in the middle of a run.
            makeCheckedCuller(row, OptionValues(row.options), CostModel{});
        }
    } catch (const RegistryError& e) {
        throw PluginError(name + ": " + e.what());
    } catch (const std::exception& e) {
        throw PluginError(name + ": registering its cullers threw: " + e.what());
    }
    for (CullerRow& row : registrar.rows) names.push_back(registry.add(std::move(row)).name);
    loadedFiles(registry).insert(canonical);
    return names;
}

std::vector<std::string> loadPlugin(const std::filesystem::path& file) {
    return loadPlugin(file, cullerRegistry());
}

}  // namespace occsim
