#include "tune/tuner.h"

#include <algorithm>
#include <thread>

#include "sim/run/stop_request.h"
#include "tune/choice.h"
#include "tune/confirm.h"
#include "tune/errors.h"
#include "tune/input.h"
#include "tune/interrupt.h"
#include "tune/progress.h"
#include "tune/sampling.h"

namespace occsim::tune {
namespace {

namespace fs = std::filesystem;

// tuned.json in the folder always belongs to the last finished session: an older one goes before
// the first run, so that an interrupted or failed session leaves none.
void prepareOutputFolder(const fs::path& out_dir) {
    fs::create_directories(out_dir);
    std::error_code ec;
    fs::remove(out_dir / "tuned.json", ec);
}

TuneSession interrupted(const SampleLog& log, bool confirming) {
    TuneSession s;
    s.end = TuneSession::End::Interrupted;
    s.interrupted_confirming = confirming;
    s.samples_logged = log.samples().size();
    s.log_file = log.file();
    return s;
}

std::vector<std::vector<FrameCounts>> frameGroups(const SampleLog& log) {
    std::vector<std::vector<FrameCounts>> groups;
    for (const LoggedRun& r : log.runs()) groups.push_back(r.frames);
    return groups;
}

// What the session ran on and what it measured, as the report and the console say it.
void describeSession(TuneResult& r, const TuneOptions& o, const CheckedInput& c,
                     const SampleLog& log) {
    r.options = &o;
    r.space = c.space;
    r.scenario_name = c.scenario.name;
    r.scenario_file = o.scenario.string();
    r.scenario_seed = c.scenario.seed;
    r.frames = c.scenario.frames;
    r.warmup_frames = c.scenario.warmup_frames;
    r.objects = c.objects;
    r.triangles = c.triangles;
    r.held_out_seed = c.held_out_seed;
    r.held_out_changes = c.held_out_effect.text();
    r.left_out = c.left_out;
    r.hardware_threads = std::thread::hardware_concurrency();
    r.log = &log;
    r.samples = log.samples();
    r.initial_samples = log.settings().initial_samples;
    for (const Sample& s : r.samples) r.objective.push_back(objectiveOf(s, o.objective));
    r.references = log.referenceSamples();
    for (const Sample& s : r.references)
        r.reference_objective.push_back(objectiveOf(s, o.objective));
    for (const LoggedRun& run : log.runs()) r.sample_error_pixels += run.error_pixels;
    r.reference_noise = log.referenceNoise();
}

// The frame-time model over every logged frame, and the response model over the samples.
void fitModels(TuneResult& r, const SampleLog& log, const ParameterSpace& space,
               const TuneOptions& o) {
    r.cost = fitFrameTimeModel(frameGroups(log), o.max_fit_iterations);
    const Observations obs = observationsOf(log, space, o.objective);
    std::vector<size_t> all(space.size());
    for (size_t j = 0; j < all.size(); ++j) all[j] = j;
    r.full_model_loo_rms =
        fitResponse(obs.xs, obs.ys, space.size(), all, o.max_fit_iterations).loo_rms;
    r.response =
        selectResponseModel(obs.xs, obs.ys, space.size(), o.max_fit_iterations, &r.dropped);
}

// The first fit that did not converge, with its name ("cost" or "response"), or none.
std::pair<const char*, const RobustFit*> unconvergedFit(const TuneResult& r) {
    for (const auto& [name, fit] :
         {std::pair<const char*, const RobustFit*>{"cost", &r.cost.fit},
          std::pair<const char*, const RobustFit*>{"response", &r.response.fit}}) {
        if (!fit->converged) return {name, fit};
    }
    return {nullptr, nullptr};
}

// The confirmation of `tuned` against `reference`: on the fitted frames, and on a variant the fit
// never saw (another seed). Throws Interrupted on Ctrl-C.
void confirmChoice(TuneResult& r, const CheckedInput& c, const TuneOptions& o, const Setting& tuned,
                   const Setting& reference, SessionRuns& session, Progress& progress) {
    const CullerRow& algorithm = *c.space.algorithm;
    Scenario held_out = c.scenario;
    held_out.seed = c.held_out_seed;
    for (const auto& run :
         {std::pair<const Scenario*, std::string>{
              &c.scenario, "fitted (seed " + std::to_string(c.scenario.seed) + ")"},
          std::pair<const Scenario*, std::string>{
              &held_out, "held out (seed " + std::to_string(held_out.seed) + ")"}}) {
        // Named, not a structured binding: clang 14 (the fuzz preset) cannot capture one.
        const Scenario* scenario = run.first;
        const std::string& variant = run.second;
        r.confirmation.push_back(confirm(
            *scenario, algorithm, variant, tuned, reference, o.repetitions, session,
            [&](const FrameEvent& e) {
                progress.setStage(
                    "confirming, " + variant + ": repetition " + std::to_string(e.repetition + 1) +
                    "/" + std::to_string(o.repetitions) + ", frame " + std::to_string(e.frame + 1) +
                    "/" + std::to_string(scenario->frames));
                progress.frameDone();
                throwIfInterrupted();
            }));
    }
}

}  // namespace

int TuneSession::exitCode() const {
    switch (end) {
        case End::Interrupted:
            return stopSignal() != 0 ? 128 + stopSignal() : kExitInterrupted;
        case End::FitFailed:
            return kExitFitFailed;
        case End::Finished:
            break;
    }
    return result.verdict.kind == Verdict::Kind::Rejected ? kExitRejected : kExitDone;
}

TuneSession runTuner(const TuneOptions& o) {
    const CheckedInput c = checkInput(o);
    auto owned_log = std::make_unique<SampleLog>(openLog(o, c));
    SampleLog& log = *owned_log;
    prepareOutputFolder(c.out_dir);

    installInterruptHandler();
    SessionRuns session{o.backend, {}};
    Progress progress(o.progress);
    progress.setWorkLeft(workLeft(o.budget - std::min<size_t>(o.budget, log.samples().size()), o,
                                  c.scenario.frames));
    progress.setBest(bestSoFar(log, c.space, o.objective));
    try {
        sample(log, c, o, progress, session);
    } catch (const Interrupted&) {
        progress.finish();
        return interrupted(log, false);
    }

    TuneSession s;
    s.out_dir = c.out_dir;
    s.log = std::move(owned_log);
    TuneResult& r = s.result;
    describeSession(r, o, c, log);
    fitModels(r, log, c.space, o);
    if (const auto [name, fit] = unconvergedFit(r); fit) {
        progress.finish();
        s.end = TuneSession::End::FitFailed;
        s.failed_model = name;
        s.ceres_summary = fit->ceres_summary;
        return s;
    }
    chooseTunedValues(r, c.space);

    // What is confirmed is what tuned.json will carry: the tuned options, and the fitted cost
    // model when asked for, the culler weighs costs and the model fits well enough (tunedSetting).
    const CullerRow& algorithm = *c.space.algorithm;
    const OptionValues base = c.scenario.culler.of(algorithm);
    const Setting reference{"paper", c.space.paper(base), std::nullopt};
    const Setting tuned = tunedSetting(algorithm, c.space.apply(base, r.tuned_values), r.cost,
                                       o.apply_cost_model, &r.cost_model_note);
    r.cost_model_applied = tuned.cost_model.has_value();
    try {
        confirmChoice(r, c, o, tuned, reference, session, progress);
    } catch (const Interrupted&) {
        progress.finish();
        return interrupted(log, true);
    }
    progress.finish();
    r.runs = session.runs;
    r.busy_runs = session.busy_runs;
    r.renderer = r.confirmation.front().renderer;
    r.verdict = judgeConfirmation(r.confirmation, r.reference_noise, referenceName(algorithm));
    s.tuned_file = tunedFile(algorithm, writtenSetting(r.verdict, tuned, reference));
    return s;
}

}  // namespace occsim::tune
