// Real runs of the tuned culler: several settings interleaved frame by frame in one
// runBenchmark() call (BenchOptions::configs), headless through the chosen backend (EGL by
// default), in measured mode (query results ready when the GPU says so), with error measured
// against ground truth. The first setting is the reference the others are divided by, so that a
// machine slowed by other work slows both alike and the ratio stays.
#pragma once

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "occsim/culling/registry/culler_options.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"
#include "tune/sample_log.h"

namespace occsim::tune {

struct Setting {
    std::string label;
    OptionValues options;  // the tuned culler's (ParameterSpace::algorithm)
    // A cost model for the tuned culler alone (CullerOptions::cost_model_of), as tuned.json
    // carries it; none: the scenario's own (usually none, calibrated at start-up).
    std::optional<CostModel> cost_model;

    // The same options and the same cost model: the same setting, whatever the label.
    bool sameSettingAs(const Setting& other) const {
        return options == other.options && cost_model == other.cost_model;
    }
};

// What every run of one tuning session shares: where it renders (--backend, --device), and the
// scene warnings it has printed, so that each is printed once a session rather than once a batch.
struct SessionRuns {
    BackendChoice backend;
    std::set<std::string> warnings_shown;
    // The runs of this session, and those on a busy machine (RunMetadata::busyMachine(): the
    // load average above the hardware threads before a run, or above twice that after it).
    uint32_t runs = 0, busy_runs = 0;
};

// Counts a finished run of the session, and whether it ran on a busy machine; returns that.
// The session says it at its end (busyMachineNote()), as bench says it of its run.
bool noteMachineLoad(SessionRuns& session, const RunMetadata& metadata);

// The scenario's own culling options with the setting's values (and cost model, if any) for
// `algorithm` swapped in.
RunConfig configOf(const Scenario& scenario, const CullerRow& algorithm, const Setting& setting);

// Runs every setting interleaved (`repetitions` times) with error measured. `on_frame` is called
// after every configuration's frame, outside the timing (progress, interruption).
BenchResult runInterleaved(const Scenario& scenario, const CullerRow& algorithm,
                           const std::vector<Setting>& settings, uint32_t repetitions,
                           SessionRuns& session,
                           const std::function<void(const FrameEvent&)>& on_frame);

// One configuration's first repetition as a log line's figures (timed frames only).
LoggedRun loggedRunOf(const occsim::RunRecord& run, uint32_t warmup_frames);

}  // namespace occsim::tune
