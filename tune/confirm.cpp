#include "tune/confirm.h"

#include "tune/measure.h"

#include <algorithm>

namespace occsim::tune {

Spread spreadOf(std::vector<double> v) {
    if (v.empty()) return {};
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    return {median, v.front(), v.back()};
}

ConfirmationRow confirm(const Scenario& scenario, const AlgorithmTraits& algorithm,
                        const std::string& variant, const OptionValues& tuned,
                        const OptionValues& paper, uint32_t repetitions, const BackendChoice& backend,
                        const std::function<void(const FrameEvent&)>& on_frame) {
    // The paper's values first: the same order as every sampling batch.
    const BenchResult result = runInterleaved(scenario, algorithm, {{"paper", paper}, {"tuned", tuned}},
                                              repetitions, backend, on_frame);
    const occsim::RunRecord& p = result.runs[0];
    const occsim::RunRecord& t = result.runs[1];

    ConfirmationRow row;
    row.variant = variant;
    row.seed = scenario.seed;
    row.frames = result.metadata.frames;
    // Where it rendered, as occsim's console names it: tuned values carry over only to the same
    // kind of renderer (docs/headless-gpu.md).
    row.renderer = result.metadata.renderer + " through " + backendLabel(result.metadata) + " (vendor " +
                   result.metadata.gl_vendor + ", driver " + result.metadata.driver + ")";
    row.repetitions = static_cast<uint32_t>(t.repetitions.size());
    std::vector<double> mean_ratios, p95_ratios;
    for (size_t r = 0; r < t.repetitions.size(); ++r) {
        mean_ratios.push_back(t.repetitions[r].frame_ms.mean / p.repetitions[r].frame_ms.mean);
        p95_ratios.push_back(t.repetitions[r].frame_ms.p95 / p.repetitions[r].frame_ms.p95);
        row.tuned_error_pixels += t.repetitions[r].error_pixels_total;
        row.paper_error_pixels += p.repetitions[r].error_pixels_total;
        row.tuned_tie_pixels += t.repetitions[r].tie_pixels_total;
        row.paper_tie_pixels += p.repetitions[r].tie_pixels_total;
        row.tuned_missed_objects += t.repetitions[r].missed_objects_total;
        row.paper_missed_objects += p.repetitions[r].missed_objects_total;
    }
    row.mean_ratio = spreadOf(mean_ratios);
    row.p95_ratio = spreadOf(p95_ratios);
    row.tuned_mean_ms = t.summary.frame_ms.mean;
    row.paper_mean_ms = p.summary.frame_ms.mean;
    row.tuned_queries = t.summary.queries_mean;
    row.paper_queries = p.summary.queries_mean;
    row.tuned_objects = t.summary.objects_mean;
    row.paper_objects = p.summary.objects_mean;
    return row;
}

}  // namespace occsim::tune
