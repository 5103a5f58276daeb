// What the viewer's file-based tests share: the scenarios folder, a file's text, and a fresh
// temporary folder of this process.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace occsim::view_files {

inline const std::filesystem::path kScenarios =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios";

inline std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline std::filesystem::path freshDir(const std::string& name) {
    // Per process: test suites of other checkouts may run at the same time on the same machine.
    const auto dir = std::filesystem::temp_directory_path() /
                     ("occsim-view-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    return dir;
}

}  // namespace occsim::view_files
