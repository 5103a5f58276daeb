#include "sim/commands/listings.h"

#include <cstdio>

#include "occsim/culling/registry/registry_text.h"
#include "render/headless_context.h"
#include "sim/commands/shared_flags.h"
#include "sim/scenario/scenario.h"
#include "sim/world/scene_info.h"

namespace occsim_cli {

CLI::App* addCullers(CLI::App& app, CullersFlags& flags) {
    CLI::App* cullers = app.add_subcommand(
        "cullers", "List the registered cullers, their traits and every option (docs/cullers.md)");
    cullers->add_flag("--markdown", flags.markdown, "As the Markdown tables of docs/cullers.md");
    addPluginFlag(cullers, flags.plugins);
    return cullers;
}

CLI::App* addDevices(CLI::App& app) {
    return app.add_subcommand("devices",
                              "List the EGL devices headless runs can use (--device "
                              "N), with vendor, renderer and driver");
}

CLI::App* addInfo(CLI::App& app, std::string& scenario) {
    CLI::App* info = app.add_subcommand(
        "info", "Print what a scenario builds (objects, triangles, BSP) without rendering");
    info->add_option("scenario", scenario, "Scenario file (JSON)")->required();
    return info;
}

int cullersCommand(const CullersFlags& flags) {
    loadPlugins(flags.plugins);
    std::printf("%s", (flags.markdown ? occsim::cullersMarkdown() : occsim::cullersText()).c_str());
    return 0;
}

// `occsim devices`: every EGL device with what a context on it reports.
int devicesCommand() {
    std::printf("OSMesa: %s\n", occsim::osmesaAvailable()
                                    ? "in this build (--backend osmesa)"
                                    : "not in this build (OCCSIM_WITH_OSMESA=OFF)");
    const std::vector<occsim::EglDeviceInfo> devices = occsim::listEglDevices();
    std::printf("EGL devices: %zu\n", devices.size());
    for (const occsim::EglDeviceInfo& d : devices) {
        std::printf("device %u (%s): ", d.index, d.kind.c_str());
        if (!d.problem.empty()) {
            std::printf("unusable: %s\n", d.problem.c_str());
            continue;
        }
        const occsim::ContextInfo& c = d.context;
        std::printf("vendor %s, renderer %s, driver %s, OpenGL %s%s\n", c.vendor.c_str(),
                    c.renderer.c_str(), c.driver.c_str(), c.version.c_str(),
                    c.gpu_time_meaningful ? "" : " (software rasteriser: gpu ms not meaningful)");
    }
    return 0;
}

int infoCommand(const std::string& scenario) {
    std::vector<std::string> warnings;
    const std::string text =
        occsim::describeScenario(occsim::parseScenarioFile(scenario), warnings);
    for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    std::printf("%s", text.c_str());
    return 0;
}

}  // namespace occsim_cli
