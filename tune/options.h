// What an occtune session is asked to do (tune/main.cpp fills it from the command line), and the
// exit codes a session ends with.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "render/headless_context.h"

namespace occsim::tune {

enum class Objective { Mean, P95 };

struct TuneOptions {
    std::filesystem::path scenario;
    uint32_t budget = 20;                        // samples, besides the references
    std::string algorithm = "statistical";       // a registered culler with tunable options
    std::vector<std::filesystem::path> plugins;  // loaded first (--plugin), like occsim's
    std::string params;                          // empty: every tunable option of the algorithm
    std::vector<std::string> bounds;             // "name=lo:hi"
    Objective objective = Objective::Mean;
    uint32_t repetitions = 3;   // of the confirmation
    std::filesystem::path out;  // default out/<scenario name>/tune
    bool resume = false;
    std::optional<uint32_t> frames;        // instead of the scenario's
    uint64_t seed = 1;                     // of the sampling design
    uint32_t batch = 4;                    // samples per interleaved run
    std::optional<uint64_t> holdout_seed;  // default: the scenario's seed + 1
    int max_fit_iterations = 200;
    // Confirm (and write) the tuned options with the fitted cost model, when it fits well enough
    // (tune/tuned_file.h). Off: the culler calibrates at start-up, as it did in every sample, so
    // the confirmation measures the setting the samples measured (docs/tuning.md, "The cost
    // model").
    bool apply_cost_model = false;
    bool progress = false;  // the progress line (stderr)
    BackendChoice backend;  // --backend, --device
    std::string command_line;
};

inline constexpr int kExitDone = 0;
inline constexpr int kExitFitFailed = 1;
inline constexpr int kExitRejected = 3;       // the confirmation rejected the tuned values
inline constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as shells report it

}  // namespace occsim::tune
