// Which occsim this is: the project version from CMake and the git commit the build was configured
// from (build_info.h.in), for `occsim --version`, `occtune --version` and summary.json.
#pragma once

#include <string>

namespace occsim {

const char* occsimVersion();  // "0.1.0": project(occsim VERSION ...) in CMakeLists.txt
const char* occsimCommit();   // `git describe --always --dirty` at configure time, or "unknown"

// "<program> 0.1.0 (commit 2cf8947-dirty)": what --version prints.
std::string versionLine(const std::string& program);

}  // namespace occsim
