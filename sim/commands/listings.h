// `occsim cullers`, `occsim devices` and `occsim info`: what is registered, what can render, what a
// scenario builds. Each prints and renders nothing (devices makes one context per device).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace occsim_cli {

struct CullersFlags {
    bool markdown = false;
    std::vector<std::string> plugins;
};

CLI::App* addCullers(CLI::App& app, CullersFlags& flags);
CLI::App* addDevices(CLI::App& app);
CLI::App* addInfo(CLI::App& app, std::string& scenario);

int cullersCommand(const CullersFlags& flags);
int devicesCommand();
int infoCommand(const std::string& scenario);

}  // namespace occsim_cli
