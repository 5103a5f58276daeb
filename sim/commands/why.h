// `occsim why RUN`: answers in words from the run folder's objects.sqlite (written by `occsim
// run|bench|regress --record objects`): why one object was drawn or left out, by configuration
// and frame; the objects each configuration drew while hidden; every object it missed.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace occsim_cli {

struct WhyFlags {
    std::string run;
    std::string object;
    int64_t frame = -1;
    std::string algo;
    bool overdraw = false;
    bool missed = false;
    uint32_t limit = 20;
    std::string view = "camera";
};

CLI::App* addWhy(CLI::App& app, WhyFlags& flags);
// Prints the answer; returns the exit code (bad input throws occsim::InputError).
int whyCommand(const WhyFlags& flags);

}  // namespace occsim_cli
