// What the tests of occsim's command line share: occsim run with its output and exit status, the
// small scenario, fresh temporary paths, and counting lines.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

#include "shell_command.h"

namespace occsim::cli_run {

using occsim::testing::Outcome;
using occsim::testing::shell;

inline Outcome runOccsim(const std::string& args) {
    return shell(std::string(OCCSIM_EXE) + " " + args);
}

inline const std::string kSmall =
    std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";

inline std::filesystem::path tempPath(const std::string& name) {
    const auto p = std::filesystem::temp_directory_path() /
                   ("occsim-cli-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(p);
    return p;
}

inline size_t lineCount(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

}  // namespace occsim::cli_run
