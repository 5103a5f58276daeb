// The test plugins' files (tests/plugins/test_plugin.cpp, one shared object per kind) and the
// helpers the plugin tests share (test_plugin_loader.cpp, test_plugins.cpp).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace occsim::testing {

inline std::filesystem::path pluginFile(const std::string& kind) {
    return std::filesystem::path(TEST_PLUGIN_DIR) / ("libtest_plugin_" + kind + ".so");
}

inline std::filesystem::path tempDir(const std::string& name) {
    namespace fs = std::filesystem;
    const fs::path p =
        fs::temp_directory_path() / ("occsim-plugins-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

inline size_t lineCount(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

}  // namespace occsim::testing
