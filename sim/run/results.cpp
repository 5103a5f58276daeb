#include "sim/run/results.h"

namespace occsim {

// The load after a run includes the run itself (llvmpipe keeps every core busy, and its threads
// count beside the main one): only a load beyond twice the hardware threads says that other work
// ran beside it. Before the run, anything beyond the hardware threads is other work.
bool RunMetadata::busyMachine() const {
    const double threads = static_cast<double>(hardware_threads);
    return threads > 0 && (load_before[0] > threads || load_after[0] > 2.0 * threads);
}
namespace {

// The first run of an algorithm with the given trait, unswept runs first (a sweep over a knob
// that applies to the reference would otherwise make one of its values the reference).
template <class Pred>
const RunSummary* findRun(const std::vector<RunRecord>& runs, Pred&& is) {
    const RunSummary* swept = nullptr;
    for (const RunRecord& r : runs) {
        if (!r.algorithm || !is(*r.algorithm)) continue;
        if (r.summary.label == r.algorithm->name) return &r.summary;
        if (!swept) swept = &r.summary;
    }
    return swept;
}

}  // namespace

std::string backendLabel(const RunMetadata& m) {
    if (m.backend == "egl")
        return "EGL device " + (m.device ? std::to_string(*m.device) : std::string("?"));
    if (m.backend == "osmesa") return "OSMesa";
    return m.backend.empty() ? "unknown backend" : m.backend;
}

std::string partialLine(const BenchResult& result) {
    if (!result.partial) return {};
    const PartialRun& p = *result.partial;
    const RunMetadata& m = result.metadata;
    std::string line = "partial: " + p.reason;
    if (m.repetitions > 1) {
        line += " in repetition " + std::to_string(p.repetition + 1) + " of " +
                std::to_string(m.repetitions);
    }
    line += " after " + std::to_string(p.frames_reached) + " of " + std::to_string(m.frames) +
            " frames; ";
    if (p.repetition == 0) {
        return line + "the " + std::to_string(p.frames_reached) +
               " whole frames are reported, nothing after them";
    }
    // A later repetition's share would mix frames of unequal counts into the medians.
    return line + "the " + std::to_string(p.repetition) +
           " whole repetitions before it are reported, its own frames are not";
}

bool nothingInView(const std::vector<RunRecord>& runs) {
    bool any_frame = false;  // without frames (a summary alone) there is nothing to tell
    for (const RunRecord& r : runs) {
        if (r.summary.objects_mean > 0) return false;
        for (const FrameStats& f : r.frames) {
            any_frame = true;
            if (f.objects_drawn > 0 || f.visible_objects > 0) return false;
        }
    }
    return any_frame;
}

double speedupOverReference(const std::vector<RunRecord>& runs, const RunSummary& s) {
    if (nothingInView(runs)) return 0.0;
    const RunSummary* ref = findRun(runs, [](const CullerRow& a) { return a.speedup_reference; });
    return ref && s.frame_ms.mean > 0 ? ref->frame_ms.mean / s.frame_ms.mean : 0.0;
}

double ratioToOracle(const std::vector<RunRecord>& runs, const RunSummary& s) {
    if (nothingInView(runs)) return 0.0;
    const RunSummary* oracle = findRun(runs, [](const CullerRow& a) { return a.oracle; });
    return oracle && oracle->frame_ms.mean > 0 ? s.frame_ms.mean / oracle->frame_ms.mean : 0.0;
}

void markParetoFront(std::vector<RunRecord>& runs) {
    std::vector<size_t> candidates;
    std::vector<double> low, high, error;
    for (size_t c = 0; c < runs.size(); ++c) {
        runs[c].pareto = false;
        if (runs[c].algorithm && runs[c].algorithm->oracle) continue;
        candidates.push_back(c);
        // The spread of the repetitions' means (a single run's range is its mean).
        const RunSummary& s = runs[c].summary;
        low.push_back(s.repetitions > 1 ? s.frame_ms_mean_min : s.frame_ms.mean);
        high.push_back(s.repetitions > 1 ? s.frame_ms_mean_max : s.frame_ms.mean);
        // Error over every repetition's frames (aggregateRepetitions): a miss in one repetition
        // keeps a culler off the front.
        error.push_back(s.error_pixels_mean);
    }
    const std::vector<bool> front = paretoFront(low, high, error);
    for (size_t i = 0; i < candidates.size(); ++i) runs[candidates[i]].pareto = front[i];
}

}  // namespace occsim
