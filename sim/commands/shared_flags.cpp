#include "sim/commands/shared_flags.h"

#include "occsim/culling/contract/input_error.h"
#include "occsim/culling/registry/plugin_loader.h"
#include "sim/commands/flag_checks.h"
#include "sim/run/crash_note.h"
#include "sim/run/stop_request.h"

namespace occsim_cli {

void addBackendFlags(CLI::App* cmd, BackendFlags& flags) {
    cmd->add_option("--backend", flags.backend,
                    "Headless OpenGL: auto (EGL, or OSMesa where EGL is missing), egl, osmesa "
                    "(docs/headless-gpu.md)");
    cmd->add_option("--device", flags.device,
                    "EGL device index (occsim devices lists them; default 0)")
        ->check(integerIn(0, 1023));
}

occsim::BackendChoice backendChoice(const BackendFlags& flags) {
    occsim::BackendChoice choice;
    const auto backend = occsim::parseBackend(flags.backend);
    if (!backend)
        throw occsim::InputError("--backend: expected auto, egl or osmesa, got '" + flags.backend +
                                 "'");
    choice.backend = *backend;
    if (flags.device >= 0) choice.device = static_cast<uint32_t>(flags.device);
    return choice;
}

void addPluginFlag(CLI::App* cmd, std::vector<std::string>& plugins) {
    cmd->add_option("--plugin", plugins,
                    "Load cullers from this shared object (repeatable; docs/plugins.md); they run "
                    "wherever the built-ins run");
}

void loadPlugins(const std::vector<std::string>& plugins) {
    for (const std::string& file : plugins) {
        try {
            occsim::loadPlugin(file);
        } catch (const occsim::PluginError& e) {
            throw occsim::givenBy("--plugin", e);
        }
    }
}

void watchFrames() {
    occsim::installStopHandlers();
    occsim::installCrashHandler();
}

}  // namespace occsim_cli
