// The flags several commands share, and what they do before a command's work: --backend and
// --device (headless rendering), --plugin (plugin cullers), and the frame watch every command that
// renders frames starts with.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "render/headless_context.h"

namespace occsim_cli {

// --backend and --device, on every command that renders headless.
struct BackendFlags {
    std::string backend = "auto";
    int64_t device = -1;
};

void addBackendFlags(CLI::App* cmd, BackendFlags& flags);
// Throws occsim::InputError for a --backend that names no backend.
occsim::BackendChoice backendChoice(const BackendFlags& flags);

void addPluginFlag(CLI::App* cmd, std::vector<std::string>& plugins);
// Plugins load before any scenario is read: a scenario may name their cullers and options.
// Throws occsim::InputError "--plugin <file>: ..." for one that cannot be loaded.
void loadPlugins(const std::vector<std::string>& plugins);

// Before a command's first frame: SIGINT and SIGTERM stop it after the frame in hand with what
// it has written (marked partial), and a crash names the configuration and frame in hand.
void watchFrames();

}  // namespace occsim_cli
