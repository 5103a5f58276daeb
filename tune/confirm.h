// The confirmation: the tuned values against the paper's, interleaved frame by frame in the same
// run, repeated, on the frames they were fitted on and on a variant the fit never saw.
#pragma once

#include "culling/culler_options.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

#include <cstdint>
#include <functional>
#include <string>

namespace occsim::tune {

struct Spread {
    double median = 0.0, min = 0.0, max = 0.0;
};

struct ConfirmationRow {
    std::string variant;  // what was run, e.g. "fitted (seed 2005)"
    uint64_t seed = 0;
    uint32_t frames = 0;
    uint32_t repetitions = 0;
    std::string renderer;  // the run's renderer, backend, device, vendor and driver
    // Per repetition: the tuned run's figure over the paper's, from the same interleaved run.
    Spread mean_ratio;
    Spread p95_ratio;
    double tuned_mean_ms = 0.0, paper_mean_ms = 0.0;  // medians over repetitions
    double tuned_queries = 0.0, paper_queries = 0.0;  // per frame
    double tuned_objects = 0.0, paper_objects = 0.0;  // drawn per frame
    int64_t tuned_error_pixels = 0, paper_error_pixels = 0;  // over every frame of every repetition
};

ConfirmationRow confirm(const Scenario& scenario, const std::string& variant, const StatisticalOptions& tuned,
                        const StatisticalOptions& paper, uint32_t repetitions, const BackendChoice& backend,
                        const std::function<void(const FrameEvent&)>& on_frame);

Spread spreadOf(std::vector<double> values);

}  // namespace occsim::tune
