#include "tune/sampling.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "occsim/culling/geometry/random.h"
#include "tune/interrupt.h"
#include "tune/measure.h"
#include "tune/response_model.h"

namespace occsim::tune {
namespace {

constexpr size_t kReferences = 2;  // runs of the paper's values per batch

// The next batch: the rest of the space-filling design first, then adaptive points.
std::vector<Point> planBatch(const SampleLog& log, const ParameterSpace& space,
                             const TuneOptions& o) {
    const LogSettings& s = log.settings();
    const Observations obs = observationsOf(log, space, o.objective);
    const size_t done = log.samples().size();
    const size_t k = std::min<size_t>(o.batch, o.budget - done);
    if (done < s.initial_samples) {
        const std::vector<Point> design = latinHypercube(s.initial_samples, space.size(), s.seed);
        const size_t end = std::min<size_t>(s.initial_samples, done + k);
        return {design.begin() + static_cast<std::ptrdiff_t>(done),
                design.begin() + static_cast<std::ptrdiff_t>(end)};
    }
    // The model the session will choose with (parameters without an effect dropped): a full
    // quadratic fitted to barely more samples than it has terms runs off at the corners.
    ResponseFit fit =
        selectResponseModel(obs.xs, obs.ys, space.size(), o.max_fit_iterations, nullptr);
    const Point optimum = minimiseOverBox(fit.model, space.paperUnitPoint());
    return nextBatch(fit, obs.xs, optimum, k, deriveSeed(s.seed, log.batches(), 0x5A3D));
}

}  // namespace

double objectiveOf(const Sample& s, Objective o) {
    return o == Objective::Mean ? s.ratio_mean : s.ratio_p95;
}

Observations observationsOf(const SampleLog& log, const ParameterSpace& space,
                            Objective objective) {
    Observations obs;
    std::vector<Sample> all = log.samples();
    const std::vector<Sample> references = log.referenceSamples();
    all.insert(all.end(), references.begin(), references.end());
    for (const Sample& s : all) {
        obs.xs.push_back(space.unitPoint(s.run->values));
        obs.ys.push_back(objectiveOf(s, objective));
    }
    return obs;
}

std::string bestSoFar(const SampleLog& log, const ParameterSpace& space, Objective objective) {
    const std::vector<Sample> samples = log.samples();
    const Sample* best = nullptr;
    for (const Sample& s : samples) {
        if (!best || objectiveOf(s, objective) < objectiveOf(*best, objective)) best = &s;
    }
    if (!best) return "";
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.3f", objectiveOf(*best, objective));
    return std::string(ratio) + " (" + space.describe(best->run->values) + ")";
}

uint64_t workLeft(size_t samples_left, const TuneOptions& o, uint32_t frames) {
    const uint64_t batches = (samples_left + o.batch - 1) / o.batch;
    return (samples_left + kReferences * batches) * frames + 2ull * 2ull * o.repetitions * frames;
}

void sample(SampleLog& log, const CheckedInput& c, const TuneOptions& o, Progress& progress,
            SessionRuns& session) {
    const ParameterSpace& space = c.space;
    const OptionValues base = c.scenario.culler.of(*space.algorithm);
    const OptionValues paper = space.paper(base);
    while (log.samples().size() < o.budget) {
        const std::vector<Point> points = planBatch(log, space, o);
        if (points.empty())
            throw std::runtime_error("no new sample point could be found in the bounds");
        const uint32_t batch = log.batches();
        // The reference values twice: the ratio of every sample shares the reference's noise,
        // which two runs halve (in variance), and their difference measures that noise. Samples
        // run without a fitted cost model (there is none yet): the scenario's own.
        std::vector<Setting> settings = {{"paper", paper, std::nullopt},
                                         {"paper (second run)", paper, std::nullopt}};
        for (size_t i = 0; i < points.size(); ++i) {
            settings.push_back({"sample " + std::to_string(log.samples().size() + i) + ": " +
                                    space.describe(space.values(points[i])),
                                space.apply(base, space.values(points[i])), std::nullopt});
        }
        const std::string stage = "samples " + std::to_string(log.samples().size()) + "/" +
                                  std::to_string(o.budget) + ", running " +
                                  std::to_string(points.size()) + " more";
        const BenchResult result = runInterleaved(
            c.scenario, *space.algorithm, settings, 1, session, [&](const FrameEvent& e) {
                progress.setStage(stage + " (frame " + std::to_string(e.frame + 1) + "/" +
                                  std::to_string(c.scenario.frames) + ")");
                progress.frameDone();
                throwIfInterrupted();
            });
        std::vector<LoggedRun> runs;
        for (size_t i = 0; i < result.runs.size(); ++i) {
            LoggedRun r = loggedRunOf(result.runs[i], c.scenario.warmup_frames);
            r.batch = batch;
            r.reference = i < kReferences;
            r.values = r.reference ? space.values(space.paperUnitPoint())
                                   : space.values(points[i - kReferences]);
            runs.push_back(std::move(r));
        }
        log.appendBatch(runs);
        progress.setBest(bestSoFar(log, space, o.objective));
    }
}

}  // namespace occsim::tune
