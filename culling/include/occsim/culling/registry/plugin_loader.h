// Loads plugin cullers (occsim/culling/plugin.h) from shared objects into the program's registry.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "occsim/culling/contract/input_error.h"

namespace occsim {

class CullerRegistry;

// A plugin that cannot be loaded: "<file>: <what was expected>", one line.
struct PluginError : InputError {
    using InputError::InputError;
};

// Loads `file` and registers its cullers in `registry`, each made once with its default options
// (so a factory that throws fails here, before any run). A file already loaded is not loaded
// again. Returns the names of the cullers it registered (none when it was already loaded).
// Throws PluginError: the file is missing, not a shared object, lacks the entry point, has another
// ABI version, or one of its rows is refused (a name already taken, an invalid descriptor, a
// factory that throws or makes nothing); a refused plugin registers none of its cullers.
std::vector<std::string> loadPlugin(const std::filesystem::path& file, CullerRegistry& registry);
// The same, into cullerRegistry().
std::vector<std::string> loadPlugin(const std::filesystem::path& file);

}  // namespace occsim
