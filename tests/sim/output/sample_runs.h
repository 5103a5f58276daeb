// Made-up runs for the report tests (test_report.cpp, test_markdown_report.cpp): records with the
// figures a table shows, and three of them as a run of three configurations would give.
#pragma once

#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "sim/run/results.h"

namespace occsim::testing {

// A run of 30 frames (25 timed) of `algorithm` labelled `label`: mean frame time, error pixels a
// frame, on the Pareto front or not.
inline RunRecord record(const std::string& label, const std::string& algorithm, double mean_ms,
                        double error_mean, bool pareto) {
    RunRecord r;
    r.algorithm = findCuller(algorithm);
    r.pareto = pareto;
    RunSummary& s = r.summary;
    s.label = label;
    s.frames = 30;
    s.timed_frames = 25;
    s.frame_ms = {mean_ms, mean_ms, mean_ms * 1.2, mean_ms * 0.8, mean_ms * 1.5};
    s.frame_ms_mean_min = s.frame_ms_mean_max = mean_ms;
    s.queries_mean = algorithm == "vfc" || algorithm == "ideal" ? 0 : 42;
    s.triangles_mean = 1000 * mean_ms;
    s.objects_mean = 10 * mean_ms;
    s.error_measured = true;
    s.error_pixels_mean = error_mean;
    s.error_pixels_total = static_cast<int64_t>(error_mean * 30);
    for (uint32_t f = 0; f < 30; ++f) {
        FrameStats fs;
        fs.frame = f;
        fs.frame_ms = mean_ms + (f % 5);
        fs.queries = static_cast<uint64_t>(s.queries_mean) + f;
        fs.triangles = static_cast<uint64_t>(s.triangles_mean) + 100 * f;
        r.frames.push_back(fs);
    }
    return r;
}

// vfc, a statistical culler with error, chc and ideal.
inline std::vector<RunRecord> sampleRuns() {
    return {record("vfc", "vfc", 20.0, 0.0, false),
            record("statistical threshold=4", "statistical", 12.0, 3.5, true),
            record("chc", "chc", 14.0, 0.0, true), record("ideal", "ideal", 6.0, 0.0, false)};
}

}  // namespace occsim::testing
