#include "tune/measure.h"

#include <stdexcept>

#include "occsim/culling/registry/registry.h"
#include "tune/errors.h"

namespace occsim::tune {
RunConfig configOf(const Scenario& scenario, const CullerRow& algorithm, const Setting& setting) {
    RunConfig config;
    config.label = setting.label;
    config.algorithm = &algorithm;
    config.culler = scenario.culler;
    config.culler.edit(algorithm) = setting.options;
    if (setting.cost_model)
        config.culler.cost_model_of.insert_or_assign(algorithm.name, *setting.cost_model);
    return config;
}

BenchResult runInterleaved(const Scenario& scenario, const CullerRow& algorithm,
                           const std::vector<Setting>& settings, uint32_t repetitions,
                           SessionRuns& session,
                           const std::function<void(const FrameEvent&)>& on_frame) {
    BenchOptions options;
    options.backend = session.backend;
    options.warnings_shown = &session.warnings_shown;
    for (const Setting& s : settings) options.configs.push_back(configOf(scenario, algorithm, s));
    options.algorithms = {options.configs.front().algorithm};
    options.measure_error = true;  // zero expected of a conservative culler: measured, not assumed
    options.repetitions = repetitions;
    // Every setting takes every place within a frame equally often: measured on library (docs/
    // tuning.md), the first place is a few per cent slower, which would otherwise flatter every
    // sample against the reference. Rotated, as the tuner's figures were measured (balanced
    // would also give each setting every predecessor equally often).
    options.frame_order = FrameOrder::rotated;
    options.command = "tune";
    options.on_frame = on_frame;
    BenchResult result = runBenchmark(scenario, options);
    noteMachineLoad(session, result.metadata);
    // A run cut short is no sample: its frames would weigh unlike the others'. A signal ends the
    // session as an interruption (the log whole), a culler that threw as a failure while running.
    if (result.partial && result.partial->signal != 0) throw Interrupted();
    if (result.partial) throw std::runtime_error(result.partial->reason);
    return result;
}

bool noteMachineLoad(SessionRuns& session, const RunMetadata& metadata) {
    ++session.runs;
    if (!metadata.busyMachine()) return false;
    ++session.busy_runs;
    return true;
}

LoggedRun loggedRunOf(const occsim::RunRecord& run, uint32_t warmup_frames) {
    LoggedRun r;
    const RunSummary& s = run.repetitions.empty() ? run.summary : run.repetitions.front();
    r.mean_ms = s.frame_ms.mean;
    r.p95_ms = s.frame_ms.p95;
    r.error_pixels = s.error_pixels_total;
    for (const FrameStats& f : run.frames) {
        if (f.frame < warmup_frames) continue;
        r.frames.push_back({f.frame_ms, static_cast<double>(f.queries),
                            static_cast<double>(f.triangles), static_cast<double>(f.objects_drawn),
                            f.wait_ms});
    }
    return r;
}

}  // namespace occsim::tune
