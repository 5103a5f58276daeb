// What the tests of merging and of the history share: fresh folders, whole files read and
// written, occsim run with its output and exit status, the check that a command refused with one
// line and left its output as it was, and history entries.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim/regress/history.h"
#include "sim/regress/history_report.h"

namespace occsim::merge_files {

namespace fs = std::filesystem;

inline fs::path freshDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("occsim-merge-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

inline std::string readFile(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void writeFile(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

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

// A history entry of machine `host`, with statistical's speedup and queries in scenario s.
inline HistoryEntry entry(const std::string& date, const std::string& host, double speedup,
                          double queries = 40) {
    HistoryEntry e;
    e.commit = "c0ffee" + date.substr(8, 2);
    e.date = date;
    e.hostname = host;
    e.cpu = "Test CPU";
    e.renderer = "llvmpipe";
    e.backend = "egl";
    e.scenarios["s"]["vfc"] = {1.0, 0, 120, 0};
    e.scenarios["s"]["statistical"] = {speedup, queries, 60, 0};
    e.scenarios["t"]["statistical"] = {2.0, 10, 20, 0};
    return e;
}

inline fs::path historyOf(const std::string& name, const std::vector<HistoryEntry>& entries) {
    const fs::path dir = freshDir(name);
    for (const HistoryEntry& e : entries) appendHistory(dir / "history", e);
    return dir / "history";
}

inline HistoryOptions windowOf(size_t n) {
    HistoryOptions o;
    o.window = n;
    return o;
}

}  // namespace occsim::merge_files
