// Everything about a tuning session's input that can be wrong, checked before any run: the
// parameters and bounds (less those the scene gives nothing to act on), the budget, the scenario
// (parsed, and its scene built once), and the
// sample log (a new session refuses to overwrite one; --resume needs one written for the same
// settings). Each problem is a TuneInputError (or the scenario layer's own errors): one line.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/scenario/scenario.h"
#include "sim/world/occluder_roles.h"
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
    // The tunable options the scene gives nothing to act on, each with why ("occluder_size: every
    // object's occluder role is explicit (11 always, 41 never): it cannot act"), left out of the
    // space and kept at their reference values.
    std::vector<std::string> left_out;
};

CheckedInput checkInput(const TuneOptions& options);

// Drops from `space` each option the scene gives nothing to act on (one acting on the occluders
// chosen by size, in a scene where every object's role is explicit) and returns why, one line
// each. Throws TuneInputError when that leaves nothing to tune.
std::vector<std::string> leaveOutInertParameters(ParameterSpace& space,
                                                 const OccluderRoleCounts& roles);

// The session's sample log: new, or read back for --resume.
SampleLog openLog(const TuneOptions& options, const CheckedInput& input);

}  // namespace occsim::tune
