// `occsim view`: a scenario in a window (docs/viewer.md): fly, switch algorithms live, record a
// camera path; or, with --script, driven by a script file. Where no window can be opened it says
// what to do instead, in one line, and exits with status 2.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace occsim_cli {

struct ViewFlags {
    std::string scenario, algorithm, size, script, out;
    bool error = false;
    std::vector<std::string> plugins;
};

CLI::App* addView(CLI::App& app, ViewFlags& flags);

int viewCommand(const ViewFlags& flags);

}  // namespace occsim_cli
