// A culling file: a scenario's "culling" section on its own, to run a scenario with other culling
// options without editing it (`occsim run|bench|regress --culling FILE`; occtune writes its
// tuned.json in this form):
//
//   {"format_version": 1, "culling": { ...the keys of a scenario's "culling" section... }}
//
// occtune's tuned.json adds "tuned_for": NAME, and is then checked as one culler's setting: NAME a
// loaded culler, culling.algorithm NAME, no other culler's options, a cost model only with
// "cullers": [NAME]. Each breach is one line naming the file and the JSON pointer.
//
// Read by the scenario parser's own strict readers (parse_culling.cpp), so the same keys, ranges
// and one-line errors apply. Applied after the scenario is parsed, it overrides what the file
// gives: "algorithm", "threshold_pixels" and "stale_results" when present, and each options object
// it holds as a whole (keys an object omits take their defaults, as in a scenario).
#pragma once

#include <filesystem>

#include "sim/scenario/json_reader.h"
#include "sim/scenario/scenario.h"

namespace occsim {

struct CullingFile {
    std::filesystem::path file;
    Json json;  // checked by readCullingFile()
};

// Reads and checks the file once (so a bad file stops a command before any run). Throws
// ScenarioError naming the file and the JSON pointer.
CullingFile readCullingFile(const std::filesystem::path& file);

// Overrides the scenario's culling options with the file's.
void applyCullingFile(const CullingFile& culling, Scenario& scenario);

}  // namespace occsim
