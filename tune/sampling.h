// The sampling loop: batches planned from the log (the rest of the space-filling design, then
// points the fitted response finds uncertain or promising) and measured beside the paper's values
// until the budget is reached, each batch appended to the log as it finishes.
#pragma once

#include <string>
#include <vector>

#include "tune/design.h"
#include "tune/input.h"
#include "tune/measure.h"
#include "tune/options.h"
#include "tune/progress.h"
#include "tune/sample_log.h"

namespace occsim::tune {

double objectiveOf(const Sample& sample, Objective objective);

// What the response model is fitted to: every sample, and every reference run at the paper's
// values (their points in the unit cube, and objective values).
struct Observations {
    std::vector<Point> xs;
    std::vector<double> ys;
};
Observations observationsOf(const SampleLog& log, const ParameterSpace& space, Objective objective);

// "0.931 (base_time=0.41 decay_a=2.2)", or "" before the first sample.
std::string bestSoFar(const SampleLog& log, const ParameterSpace& space, Objective objective);

// Rendered frames (one configuration's each) still to come: samples, references, confirmation.
uint64_t workLeft(size_t samples_left, const TuneOptions& options, uint32_t frames);

// Measures batches until the log holds options.budget samples. Throws Interrupted on SIGINT (the
// batch in progress is dropped; the log keeps every finished one).
void sample(SampleLog& log, const CheckedInput& input, const TuneOptions& options,
            Progress& progress, SessionRuns& session);

}  // namespace occsim::tune
