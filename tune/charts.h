// The tuner's gnuplot charts (sim/output/plots.h runs gnuplot and publishes them whole):
//   tune-<parameter>   every sample's objective against that parameter, the fitted response
//                      along it (the other parameters at their tuned values) with a band of one
//                      standard deviation, the reference value (the paper's for `statistical`, the
//                      culler's default for any other) and the tuned value;
//   tune-cost-model    every fitted frame's measured time against the cost model's prediction.
#pragma once

#include <filesystem>
#include <vector>

#include "sim/output/plots.h"
#include "tune/frame_time_model.h"
#include "tune/parameters.h"
#include "tune/response_model.h"
#include "tune/sample_log.h"

namespace occsim::tune {

struct ChartInput {
    const ParameterSpace& space;
    const std::vector<Sample>& samples;
    const std::vector<double>& objective;            // per sample: the ratio that was fitted
    const std::vector<Sample>& references;           // reference runs (referenceName())
    const std::vector<double>& reference_objective;  // per reference run
    const char* objective_name;                      // "mean" or "p95"
    const ResponseFit& response;
    const Point& tuned;                      // in the unit cube
    const std::vector<bool>& kept_at_paper;  // per parameter
    const FrameTimeModel& cost;
    const std::vector<LoggedRun>& runs;  // every run whose frames the cost model fitted
};

PlotResult writeTuneCharts(const ChartInput& input, const std::filesystem::path& out_dir);

}  // namespace occsim::tune
