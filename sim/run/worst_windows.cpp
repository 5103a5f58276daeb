#include "sim/run/worst_windows.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "sim/run/results.h"

namespace occsim {
namespace {

// One frame's time over the reference's; a reference frame that took no time counts as a tiny one.
double frameRatio(const FrameStats& f, const FrameStats& ref) {
    return f.frame_ms / std::max(ref.frame_ms, 1e-9);
}

WorstWindow describeWindow(const std::vector<FrameStats>& frames,
                           const std::vector<FrameStats>& reference, uint32_t first, uint32_t w,
                           double ratio) {
    WorstWindow win;
    win.first_frame = first;
    win.frames = w;
    win.ratio = ratio;
    double worst = -1.0;
    bool error = true;
    int64_t error_pixels = 0, missed = 0;
    for (uint32_t i = first; i < first + w; ++i) {
        const FrameStats &f = frames[i], &r = reference[i];
        win.frame_ms_mean += f.frame_ms;
        win.reference_frame_ms_mean += r.frame_ms;
        win.objects_mean += static_cast<double>(f.objects_drawn);
        win.reference_objects_mean += static_cast<double>(r.objects_drawn);
        win.triangles_mean += static_cast<double>(f.triangles);
        win.reference_triangles_mean += static_cast<double>(r.triangles);
        win.queries_mean += static_cast<double>(f.queries);
        win.wait_ms_mean += f.wait_ms;
        error &= f.error_pixels >= 0;
        error_pixels += std::max<int64_t>(f.error_pixels, 0);
        missed += std::max<int64_t>(f.missed_objects, 0);
        if (const double q = frameRatio(f, r); q > worst) {
            worst = q;
            win.worst_frame = f.frame;
            win.worst_frame_ms = f.frame_ms;
            win.worst_reference_frame_ms = r.frame_ms;
        }
    }
    const double n = w;
    for (double* mean : {&win.frame_ms_mean, &win.reference_frame_ms_mean, &win.objects_mean,
                         &win.reference_objects_mean, &win.triangles_mean,
                         &win.reference_triangles_mean, &win.queries_mean, &win.wait_ms_mean}) {
        *mean /= n;
    }
    if (error) {
        win.error_pixels = error_pixels;
        win.missed_objects = missed;
    }
    return win;
}

// The first run whose algorithm has the trait, unswept runs first (as results.cpp finds them).
template <class Pred>
int firstRun(const std::vector<RunRecord>& runs, Pred&& is) {
    int swept = -1;
    for (size_t c = 0; c < runs.size(); ++c) {
        const RunRecord& r = runs[c];
        if (!r.algorithm || !is(*r.algorithm)) continue;
        if (r.summary.label == r.algorithm->name) return static_cast<int>(c);
        if (swept < 0) swept = static_cast<int>(c);
    }
    return swept;
}

}  // namespace

std::vector<WorstWindow> findWorstWindows(const std::vector<FrameStats>& frames,
                                          const std::vector<FrameStats>& reference,
                                          uint32_t warmup_frames, uint32_t window, size_t count) {
    const size_t n = std::min(frames.size(), reference.size());
    if (n <= warmup_frames || window == 0) return {};
    const auto w = static_cast<uint32_t>(std::min<size_t>(window, n - warmup_frames));
    // The ratio of every window that starts at s (negative: its reference took no time).
    std::vector<double> ratio(n - w + 1, -1.0);
    for (size_t s = warmup_frames; s + w <= n; ++s) {
        double a = 0, b = 0;
        for (size_t i = s; i < s + w; ++i) {
            a += frames[i].frame_ms;
            b += reference[i].frame_ms;
        }
        if (b > 0) ratio[s] = a / b;
    }
    std::vector<WorstWindow> chosen;
    while (chosen.size() < count) {
        long best = -1;
        for (size_t s = warmup_frames; s + w <= n; ++s) {
            if (ratio[s] < 0) continue;
            const bool overlaps = std::any_of(chosen.begin(), chosen.end(), [&](const auto& c) {
                return std::labs(static_cast<long>(s) - static_cast<long>(c.first_frame)) < w;
            });
            if (!overlaps && (best < 0 || ratio[s] > ratio[static_cast<size_t>(best)]))
                best = static_cast<long>(s);
        }
        if (best < 0) break;
        const auto s = static_cast<uint32_t>(best);
        chosen.push_back(describeWindow(frames, reference, s, w, ratio[s]));
    }
    return chosen;
}

std::vector<FrameStats> medianFrames(const RunRecord& record) {
    if (record.later_repetitions.empty()) return record.frames;
    std::vector<const std::vector<FrameStats>*> reps = {&record.frames};
    for (const auto& later : record.later_repetitions) reps.push_back(&later);
    size_t n = record.frames.size();
    for (const auto* r : reps) n = std::min(n, r->size());
    std::vector<FrameStats> out(record.frames.begin(),
                                record.frames.begin() + static_cast<long>(n));
    std::vector<double> values(reps.size());
    auto median = [&](auto field, size_t i) {
        for (size_t k = 0; k < reps.size(); ++k)
            values[k] = static_cast<double>(field((*reps[k])[i]));
        return distributionOf(values).median;
    };
    for (size_t i = 0; i < n; ++i) {
        FrameStats& f = out[i];
        f.frame_ms = median([](const FrameStats& s) { return s.frame_ms; }, i);
        f.wait_ms = median([](const FrameStats& s) { return s.wait_ms; }, i);
        f.cull_cpu_ms = median([](const FrameStats& s) { return s.cull_cpu_ms; }, i);
        f.queries = static_cast<uint64_t>(
            std::llround(median([](const FrameStats& s) { return s.queries; }, i)));
        f.objects_drawn = static_cast<uint64_t>(
            std::llround(median([](const FrameStats& s) { return s.objects_drawn; }, i)));
        f.triangles = static_cast<uint64_t>(
            std::llround(median([](const FrameStats& s) { return s.triangles; }, i)));
        f.error_pixels =
            std::llround(median([](const FrameStats& s) { return s.error_pixels; }, i));
        f.missed_objects =
            std::llround(median([](const FrameStats& s) { return s.missed_objects; }, i));
    }
    return out;
}

int windowReference(const std::vector<RunRecord>& runs) {
    const int oracle = firstRun(runs, [](const CullerRow& a) { return a.oracle; });
    if (oracle >= 0) return oracle;
    return firstRun(runs, [](const CullerRow& a) { return a.speedup_reference; });
}

int markWorstWindows(std::vector<RunRecord>& runs, uint32_t warmup_frames) {
    const int ref = windowReference(runs);
    for (RunRecord& r : runs) r.worst_windows.clear();
    // A camera that sees nothing gives frame times of empty frames: their ratios are noise, as
    // speedups are then (nothingInView).
    if (ref < 0 || nothingInView(runs)) return ref;
    const std::vector<FrameStats> reference = medianFrames(runs[static_cast<size_t>(ref)]);
    for (size_t c = 0; c < runs.size(); ++c) {
        if (static_cast<int>(c) == ref || (runs[c].algorithm && runs[c].algorithm->oracle))
            continue;
        runs[c].worst_windows = findWorstWindows(medianFrames(runs[c]), reference, warmup_frames);
    }
    return ref;
}

}  // namespace occsim
