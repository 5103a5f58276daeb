// What a tuning session found, for the report (report.h) and the console.
#pragma once

#include <string>
#include <vector>

#include "tune/confirm.h"
#include "tune/frame_time_model.h"
#include "tune/options.h"
#include "tune/parameters.h"
#include "tune/response_model.h"
#include "tune/sample_log.h"

namespace occsim::tune {

struct TuneResult {
    const TuneOptions* options = nullptr;
    ParameterSpace space;
    std::string scenario_name;
    std::string scenario_file;
    uint64_t scenario_seed = 0;
    uint32_t frames = 0, warmup_frames = 0;
    uint32_t objects = 0;
    uint64_t triangles = 0;
    std::string renderer;
    uint32_t hardware_threads = 0;

    const SampleLog* log = nullptr;
    std::vector<Sample> samples;
    std::vector<double> objective;   // per sample: the fitted ratio
    std::vector<Sample> references;  // the reference runs, as ratios to their batch's
    std::vector<double> reference_objective;
    uint32_t initial_samples = 0;
    int64_t sample_error_pixels = 0;  // over every frame of every sample and reference
    double reference_noise = 0.0;     // SampleLog::referenceNoise()

    FrameTimeModelFit cost;
    ResponseFit response;
    std::vector<size_t> dropped;      // parameters the fit found no effect of, in order dropped
    double full_model_loo_rms = 0.0;  // before any was dropped

    Point tuned_unit;
    std::vector<double> tuned_values;
    std::vector<bool> kept_at_paper;      // per parameter
    std::vector<std::string> bounds_hit;  // per parameter: "lower", "upper" or "" (ParameterSpace)
    double predicted_tuned = 0.0, predicted_paper = 0.0;
    double predicted_tuned_sd = 0.0;  // standard deviation of that prediction

    // The fitted cost model was applied in the confirmation runs (tune/tuned_file.h:
    // tunedSetting()); when the culler weighs costs and it was not, the one line that says why.
    bool cost_model_applied = false;
    std::string cost_model_note;

    // The held-out variant's seed, and what it changes in this scene (SeedEffect::text(): "the
    // layout of the scene and the movers' starts and motions", or "nothing").
    uint64_t held_out_seed = 0;
    std::string held_out_changes;
    // Tunable options the scene gives nothing to act on, left out of the fit, each with why.
    std::vector<std::string> left_out;
    std::vector<ConfirmationRow> confirmation;  // fitted, then held out
    // This session's runs and those on a busy machine (SessionRuns): its timings are not results.
    uint32_t runs = 0, busy_runs = 0;
    Verdict verdict;                 // judgeConfirmation() of them
    std::vector<std::string> files;  // written, in out_dir
    std::string charts_message;
};

const char* objectiveName(Objective objective);

}  // namespace occsim::tune
