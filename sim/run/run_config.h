// What a benchmark runs: one configuration per algorithm; with a sweep, one per value of the swept
// option for the algorithms it applies to (the others run once, as references); with an ablation,
// the algorithm as configured plus once with each of its mechanisms switched off.
//
// A sweep is written "[algorithm:]key=v1,v2,...": key is threshold_pixels or stale_results (the
// knobs every query-based culler shares) or an option key of a culler's descriptor (`occsim
// cullers` lists them), and applies to every listed algorithm that has it, or only to the one
// named before the colon.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "occsim/culling/registry/culler_options.h"
#include "occsim/culling/registry/registry.h"

namespace occsim {

struct RunConfig {
    std::string label;                     // "statistical", or "statistical base_time=0.3"
    const CullerRow* algorithm = nullptr;  // a registered culler
    CullerOptions culler;                  // with the approximation knobs
    // The culling file its options came from (bench --algos NAME@FILE), recorded in summary.json;
    // empty for the scenario's own.
    std::string culling_file = {};
};

struct Sweep {
    std::string algorithm;  // empty: every listed algorithm with the key
    std::string parameter;  // the option key
    std::vector<double> values;
};

// The keys shared by every culler that issues queries (culling.threshold_pixels and
// culling.stale_results), which a sweep may name beside the cullers' own options.
const std::vector<OptionSpec>& sharedQueryOptions();

// Throws std::invalid_argument with a one-line reason: malformed text, an unknown algorithm, a key
// no listed algorithm has, a value of the wrong type or out of its range, a value listed twice
// (booleans compare as values: true and 1 are the same value).
Sweep parseSweep(const std::string& text, const std::vector<const CullerRow*>& algorithms);

// Throws std::invalid_argument when a swept value makes an algorithm's options invalid, or when
// `ablate` names an algorithm not listed or one with no mechanism to switch off, or when two
// configurations would be the same culler with the same option values (a sweep value that the
// ablation also switches off): every configuration is unique.
std::vector<RunConfig> planConfigs(const std::vector<const CullerRow*>& algorithms,
                                   const CullerOptions& base, const std::optional<Sweep>& sweep,
                                   const std::string& ablate = {});

}  // namespace occsim
