// The algorithms a run or bench is given (--algo, --algos), each a registered culler or
// NAME@FILE: the culler with a culling file's options (occtune's tuned.json, sim/scenario/
// culling_file.h) applied over the scenario's, run as a configuration of its own beside the
// others, interleaved, labelled NAME@<file stem> ("statistical+@tuned"), so that a tuned file is
// measured against the defaults in one run. FILE must be a culling file for NAME ("tuned_for":
// NAME, or culling.algorithm NAME); a missing or invalid file, or one for another culler, is one
// line naming the flag and the file, exit 2, before any run.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "sim/run/run_config.h"
#include "sim/scenario/culling_file.h"
#include "sim/scenario/scenario.h"

namespace occsim_cli {

struct AlgorithmEntry {
    const occsim::CullerRow* algorithm = nullptr;
    std::string label;                           // "statistical+", or "statistical+@tuned"
    std::optional<occsim::CullingFile> culling;  // NAME@FILE: the file, read and checked
};

// `flag`'s comma-separated lists as given: every name registered, every file a culling file for
// its culler, no entry twice, none empty (a trailing comma).
std::vector<AlgorithmEntry> algorithmEntries(const std::string& flag,
                                             const std::vector<std::string>& lists);

// The plain cullers among the entries, each once: what a sweep and an ablation apply to.
std::vector<const occsim::CullerRow*> plainAlgorithms(const std::vector<AlgorithmEntry>& entries);

bool anyCullingFile(const std::vector<AlgorithmEntry>& entries);

// The configurations in the entries' order: a plain culler's as planConfigs() plans them (with
// the sweep and the ablation), a NAME@FILE's as the scenario with FILE applied configures NAME.
// Throws std::invalid_argument as planConfigs() does.
std::vector<occsim::RunConfig> entryConfigs(const std::vector<AlgorithmEntry>& entries,
                                            const occsim::Scenario& scenario,
                                            const std::optional<occsim::Sweep>& sweep,
                                            const std::string& ablate);

}  // namespace occsim_cli
