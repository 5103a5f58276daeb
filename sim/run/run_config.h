// What a benchmark runs: one configuration per algorithm, or, with a sweep, one per algorithm and
// value of the swept knob for the algorithms the knob applies to (the others run once, as
// references). A sweep is written "name=v1,v2,..." (docs/cli.md lists the names).
#pragma once

#include "culling/algorithms.h"
#include "culling/culler_options.h"

#include <optional>
#include <string>
#include <vector>

namespace occsim {

struct RunConfig {
    std::string label;                         // "statistical", or "statistical base_time=0.3"
    const AlgorithmTraits* algorithm = nullptr;  // from algorithms() (culling/algorithms.h)
    CullerOptions culler;                      // with the approximation knobs
};

struct Sweep {
    std::string parameter;
    std::vector<double> values;
};

// The sweepable knobs: name, unit and what they apply to, for help texts and errors.
struct SweepParameter {
    const char* name;
    const char* description;
};
const std::vector<SweepParameter>& sweepParameters();

// Throws std::invalid_argument with a one-line reason (unknown name, bad or out-of-range value).
Sweep parseSweep(const std::string& text);

// Throws std::invalid_argument when a swept value makes an algorithm's options invalid.
std::vector<RunConfig> planConfigs(const std::vector<const AlgorithmTraits*>& algorithms,
                                   const CullerOptions& base, const std::optional<Sweep>& sweep);

}  // namespace occsim
