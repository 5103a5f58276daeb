#include "tune/tuner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <thread>

#include "sim/output/atomic_file.h"
#include "tune/charts.h"
#include "tune/confirm.h"
#include "tune/errors.h"
#include "tune/input.h"
#include "tune/interrupt.h"
#include "tune/progress.h"
#include "tune/report.h"
#include "tune/result.h"
#include "tune/sampling.h"
#include "tune/tuned_file.h"

namespace occsim::tune {
namespace {

namespace fs = std::filesystem;

std::vector<std::vector<FrameCounts>> frameGroups(const SampleLog& log) {
    std::vector<std::vector<FrameCounts>> groups;
    for (const LoggedRun& r : log.runs()) groups.push_back(r.frames);
    return groups;
}

std::string costModelJson(const FrameTimeModelFit& f) {
    const FrameTimeModel& m = f.model;
    const nlohmann::json j = {
        {"model",
         "frame_ms = constant_ms + query_ms*queries + kilotriangle_ms*triangles/1000 + "
         "draw_ms*objects_drawn + "
         "wait_factor*wait_ms"},
        {"constant_ms", m.constant_ms},
        {"query_ms", m.query_ms},
        {"triangle_ms", m.triangleMs()},
        {"kilotriangle_ms", m.kilotriangle_ms},
        {"draw_ms", m.draw_call_ms},
        {"wait_factor", m.wait_factor},
        {"frames", f.frames},
        {"runs", f.groups},
        {"residual_rms_ms", f.residual_rms_ms},
        {"heldout_rms_ms",
         std::isnan(f.heldout_rms_ms) ? nlohmann::json(nullptr) : nlohmann::json(f.heldout_rms_ms)},
        {"ceres", f.fit.ceres_summary}};
    return j.dump(2) + "\n";
}

void printInterrupted(const SampleLog& log, const TuneOptions& o, bool confirming) {
    std::string resume = o.command_line;
    if (resume.find("--resume") == std::string::npos) resume += " --resume";
    std::fprintf(stderr,
                 "occtune: interrupted %s: %zu of %u samples are in %s (whole); no tuned.json "
                 "written. Resume with: %s\n",
                 confirming ? "during the confirmation" : "while sampling", log.samples().size(),
                 o.budget, log.file().string().c_str(), resume.c_str());
}

}  // namespace

int runTuner(const TuneOptions& o) {
    const CheckedInput c = checkInput(o);
    SampleLog log = openLog(o, c);
    fs::create_directories(c.out_dir);
    // tuned.json in the folder always belongs to the last finished session.
    std::error_code ec;
    fs::remove(c.out_dir / "tuned.json", ec);

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
        printInterrupted(log, o, false);
        return kExitInterrupted;
    }

    TuneResult r;
    r.options = &o;
    r.space = c.space;
    r.scenario_name = c.scenario.name;
    r.scenario_file = o.scenario.string();
    r.scenario_seed = c.scenario.seed;
    r.frames = c.scenario.frames;
    r.warmup_frames = c.scenario.warmup_frames;
    r.objects = c.objects;
    r.triangles = c.triangles;
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

    // The models.
    r.cost = fitFrameTimeModel(frameGroups(log), o.max_fit_iterations);
    const Observations obs = observationsOf(log, c.space, o.objective);
    std::vector<size_t> all(c.space.size());
    for (size_t j = 0; j < all.size(); ++j) all[j] = j;
    r.full_model_loo_rms =
        fitResponse(obs.xs, obs.ys, c.space.size(), all, o.max_fit_iterations).loo_rms;
    r.response =
        selectResponseModel(obs.xs, obs.ys, c.space.size(), o.max_fit_iterations, &r.dropped);
    for (const auto& [name, fit] :
         {std::pair<const char*, const RobustFit*>{"cost", &r.cost.fit},
          std::pair<const char*, const RobustFit*>{"response", &r.response.fit}}) {
        if (!fit->converged) {
            progress.finish();
            std::fprintf(
                stderr,
                "occtune: the %s model fit did not converge; no tuned.json written. Ceres: %s\n",
                name, fit->ceres_summary.c_str());
            return kExitFitFailed;
        }
    }

    // The choice: the model's minimum within the bounds; parameters it does not depend on stay at
    // the paper's values.
    const Point paper_unit = c.space.paperUnitPoint();
    r.tuned_unit = minimiseOverBox(r.response.model, paper_unit);
    r.tuned_values = c.space.values(r.tuned_unit);
    r.kept_at_paper.assign(c.space.size(), true);
    for (size_t j : r.response.model.active) r.kept_at_paper[j] = false;
    for (size_t j = 0; j < c.space.size(); ++j) {
        if (r.kept_at_paper[j]) r.tuned_values[j] = c.space.parameters[j].paper_value;
    }
    r.bounds_hit = c.space.boundsHit(r.tuned_values);
    for (size_t j = 0; j < c.space.size(); ++j) {
        if (r.kept_at_paper[j]) r.bounds_hit[j].clear();
    }
    r.predicted_tuned = r.response.model.predict(r.tuned_unit);
    r.predicted_tuned_sd = r.response.predict(r.tuned_unit).stddev;
    r.predicted_paper = r.response.model.predict(paper_unit);

    // The confirmation: on the fitted frames, and on a variant the fit never saw (another seed).
    const AlgorithmTraits& algorithm = *c.space.algorithm;
    const OptionValues base = c.scenario.culler.of(algorithm);
    const OptionValues paper = c.space.paper(base);
    const OptionValues tuned = c.space.apply(base, r.tuned_values);
    Scenario held_out = c.scenario;
    held_out.seed = o.holdout_seed.value_or(c.scenario.seed + 1);
    try {
        for (const auto& run :
             {std::pair<const Scenario*, std::string>{
                  &c.scenario, "fitted (seed " + std::to_string(c.scenario.seed) + ")"},
              std::pair<const Scenario*, std::string>{
                  &held_out, "held out (seed " + std::to_string(held_out.seed) + ")"}}) {
            // Named, not a structured binding: clang 14 (the fuzz preset) cannot capture one.
            const Scenario* scenario = run.first;
            const std::string& variant = run.second;
            r.confirmation.push_back(confirm(*scenario, algorithm, variant, tuned, paper,
                                             o.repetitions, session, [&](const FrameEvent& e) {
                                                 progress.setStage(
                                                     "confirming, " + variant + ": repetition " +
                                                     std::to_string(e.repetition + 1) + "/" +
                                                     std::to_string(o.repetitions) + ", frame " +
                                                     std::to_string(e.frame + 1) + "/" +
                                                     std::to_string(scenario->frames));
                                                 progress.frameDone();
                                                 throwIfInterrupted();
                                             }));
        }
    } catch (const Interrupted&) {
        progress.finish();
        printInterrupted(log, o, true);
        return kExitInterrupted;
    }
    progress.finish();
    r.renderer = r.confirmation.front().renderer;

    // The files: tuned.json last, so that its presence means the session finished.
    const TunedFile tuned_file = tunedFile(algorithm, tuned, r.cost.model);
    writeFileAtomically(c.out_dir / "cost_model.json", costModelJson(r.cost));
    r.files.push_back("cost_model.json");
    const PlotResult charts =
        writeTuneCharts({c.space, r.samples, r.objective, r.references, r.reference_objective,
                         objectiveName(o.objective), r.response, r.tuned_unit, r.kept_at_paper,
                         r.cost.model, log.runs()},
                        c.out_dir);
    r.charts_message = charts.message;
    r.files.insert(r.files.end(), charts.files.begin(), charts.files.end());
    r.verdict = judgeConfirmation(r.confirmation, r.dropped.size() == c.space.size());
    writeFileAtomically(c.out_dir / "report.md", reportMarkdown(r));
    // A result its own confirmation rejects is kept under a name that says so, and no tuned.json
    // (not even one left from before) stands beside it to be applied by mistake.
    std::filesystem::remove(c.out_dir / (r.verdict.kind == Verdict::Kind::Rejected
                                             ? "tuned.json"
                                             : "tuned.rejected.json"));
    writeFileAtomically(c.out_dir / r.verdict.fileName(), tuned_file.text);

    std::printf("%s, %s: %zu samples, %s frame-time ratio to the reference values\n",
                c.scenario.name.c_str(), algorithm.name.c_str(), r.samples.size(),
                objectiveName(o.objective));
    for (size_t j = 0; j < c.space.size(); ++j) {
        const TunableParameter& p = c.space.parameters[j];
        std::printf(
            "  %-22s reference %-8.4g tuned %-8.4g%s\n", p.name.c_str(), p.paper_value,
            r.tuned_values[j],
            r.kept_at_paper[j] ? "  (no effect beyond noise: kept at the reference value)" : "");
    }
    for (const std::string& line : boundWarnings(r)) std::printf("%s\n", line.c_str());
    if (!tuned_file.note.empty()) std::printf("%s\n", tuned_file.note.c_str());
    std::printf(
        "cost model: %.4g ms/query, %.4g ms/1000 triangles, %.4g ms/draw, %.4g ms constant "
        "(residual RMS %.2f ms)\n",
        r.cost.model.query_ms, r.cost.model.kilotriangle_ms, r.cost.model.draw_call_ms,
        r.cost.model.constant_ms, r.cost.residual_rms_ms);
    std::printf(
        "response model: predicted ratio %.3f +/- %.3f at the tuned values; leave-one-out error "
        "%.4f\n",
        r.predicted_tuned, r.predicted_tuned_sd, r.response.loo_rms);
    std::printf("%s", confirmationTable(r).c_str());
    if (tuned_file.weighs_costs && !tuned_file.has_cost_option) {
        std::printf(
            "the fitted cost model is 0 for queries, triangles and draw calls: it is in "
            "cost_model.json only, not in tuned.json\n");
    }
    if (!charts.ok && !charts.message.empty()) std::printf("%s\n", charts.message.c_str());
    std::printf("verdict: %s: %s\n", r.verdict.name(), r.verdict.reason.c_str());
    std::printf("written: %s/{%s,report.md,cost_model.json,samples.jsonl}\n",
                c.out_dir.string().c_str(), r.verdict.fileName());
    return r.verdict.kind == Verdict::Kind::Rejected ? kExitRejected : kExitDone;
}

}  // namespace occsim::tune
