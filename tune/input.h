// Everything about a tuning session's input that can be wrong, checked before any run: the
// parameters and bounds, the budget, the scenario (parsed, and its scene built once), and the
// sample log (a new session refuses to overwrite one; --resume needs one written for the same
// settings). Each problem is a TuneInputError (or the scenario layer's own errors): one line.
#pragma once

#include <cstdint>
#include <filesystem>

#include "sim/scenario/scenario.h"
#include "sim/world/seed_effect.h"
#include "tune/options.h"
#include "tune/parameters.h"
#include "tune/sample_log.h"

namespace occsim::tune {

struct CheckedInput {
    ParameterSpace space;
    Scenario scenario;  // with --frames applied
    LogSettings settings;
    std::filesystem::path out_dir;
    std::filesystem::path log_file;
    uint32_t objects = 0;
    uint64_t triangles = 0;
    // The held-out variant's seed, and what it changes in this scene (the held-out scene is built
    // here too, so that a seed whose scene cannot be built fails before any run).
    uint64_t held_out_seed = 0;
    SeedEffect held_out_effect;
};

CheckedInput checkInput(const TuneOptions& options);

// The session's sample log: new, or read back for --resume.
SampleLog openLog(const TuneOptions& options, const CheckedInput& input);

}  // namespace occsim::tune
