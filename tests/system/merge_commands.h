// occsim run as the tests of merging and of the history run it: its output and exit status, and
// the check that a command refused with one line and left its output as it was. The files they
// share: tests/support/merge_files.h.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "merge_files.h"

namespace occsim::merge_files {

struct Command {
    int status = -1;
    std::string output;  // stdout and stderr
};

inline Command runOccsim(const std::string& args) {
    const std::string command = std::string(OCCSIM_EXE) + " " + args + " 2>&1";
    Command c;
    FILE* pipe = popen(command.c_str(), "r");
    std::array<char, 4096> buf{};
    while (fgets(buf.data(), buf.size(), pipe)) c.output += buf.data();
    const int status = pclose(pipe);
    c.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return c;
}

// The command refuses with one line naming `expected`, exit 2, and `out` is as it was.
inline void expectRefused(const std::string& args, const std::string& expected,
                          const fs::path& out) {
    const std::string before = readFile(out / "report.md");
    const Command c = runOccsim(args);
    EXPECT_EQ(c.status, 2) << c.output;
    EXPECT_EQ(std::count(c.output.begin(), c.output.end(), '\n'), 1) << c.output;
    EXPECT_NE(c.output.find(expected), std::string::npos) << c.output;
    EXPECT_EQ(readFile(out / "report.md"), before) << "the earlier report was overwritten";
}

}  // namespace occsim::merge_files
