// Runs a shell command for the end-to-end tests (the executables, ldd, xvfb-run): its exit code
// and everything it printed, stdout and stderr together.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace occsim::testing {

struct Outcome {
    int exit_code = -1;
    std::string output;  // stdout and stderr together
};

inline Outcome shell(const std::string& command) {
    Outcome out;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return out;
    std::array<char, 4096> buffer{};
    while (fgets(buffer.data(), buffer.size(), pipe)) out.output += buffer.data();
    const int status = pclose(pipe);
    out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return out;
}

}  // namespace occsim::testing
