#include "sim/run/frame_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace occsim {

Distribution distributionOf(std::vector<double> values) {
    Distribution d;
    if (values.empty()) return d;
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    d.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(n);
    d.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    // Nearest-rank percentile: the smallest value with at least 95% of the values at or below it.
    const size_t rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(n)));
    d.p95 = values[std::clamp<size_t>(rank, 1, n) - 1];
    d.min = values.front();
    d.max = values.back();
    return d;
}

namespace {

// Adds to the shadow error totals, which stay -1 (not measured) until the first count.
void addShadowCounts(RunSummary& s, int64_t error_pixels, int64_t missed_casters,
                     int64_t tie_pixels) {
    s.shadow_error_pixels_total = std::max<int64_t>(s.shadow_error_pixels_total, 0) + error_pixels;
    s.missed_casters_total = std::max<int64_t>(s.missed_casters_total, 0) + missed_casters;
    s.shadow_tie_pixels_total = std::max<int64_t>(s.shadow_tie_pixels_total, 0) + tie_pixels;
}

// The shadow pass's figures (FrameStats::shadow_*): means over the timed frames that had a pass,
// error totals over every frame that measured it.
void summarizeShadows(const std::vector<FrameStats>& frames, uint32_t warmup_frames,
                      RunSummary& s) {
    double casters = 0, queries = 0, cpu = 0, gpu = 0, seen = 0, shading_cpu = 0, shading_gpu = 0;
    uint32_t passes = 0, gpu_passes = 0, measured = 0, shadings = 0, gpu_shadings = 0;
    for (const FrameStats& f : frames) {
        if (f.shadow_error_pixels >= 0) {
            ++measured;
            seen += static_cast<double>(f.shadow_seen_casters);
            addShadowCounts(s, f.shadow_error_pixels, f.missed_casters, f.shadow_tie_pixels);
        }
        if (f.frame < warmup_frames || f.shadow_casters < 0) continue;
        ++passes;
        casters += static_cast<double>(f.shadow_casters);
        queries += static_cast<double>(std::max<int64_t>(f.shadow_queries, 0));
        cpu += f.shadow_cpu_ms;
        if (f.shadow_gpu_ms >= 0) {
            ++gpu_passes;
            gpu += f.shadow_gpu_ms;
        }
        if (f.shading_cpu_ms >= 0) {
            ++shadings;
            shading_cpu += f.shading_cpu_ms;
        }
        if (f.shading_gpu_ms >= 0) {
            ++gpu_shadings;
            shading_gpu += f.shading_gpu_ms;
        }
    }
    if (shadings > 0) s.shading_cpu_ms_mean = shading_cpu / shadings;
    if (gpu_shadings > 0) s.shading_gpu_ms_mean = shading_gpu / gpu_shadings;
    if (passes > 0) {
        s.shadow_casters_mean = casters / passes;
        s.shadow_queries_mean = queries / passes;
        s.shadow_cpu_ms_mean = cpu / passes;
    }
    if (gpu_passes > 0) s.shadow_gpu_ms_mean = gpu / gpu_passes;
    if (measured > 0) s.shadow_seen_casters_mean = seen / measured;
}

}  // namespace

RunSummary summarize(const std::string& label, const std::vector<FrameStats>& frames,
                     uint32_t warmup_frames) {
    RunSummary s;
    s.label = label;
    s.frames = static_cast<uint32_t>(frames.size());
    std::vector<double> frame_ms, gpu_ms;
    bool gpu_measured = true;
    double cull = 0, wait = 0, update = 0, queries = 0, objects = 0, triangles = 0;
    double executed_objects = 0, executed_triangles = 0, read_backs = 0;
    std::array<double, 3> phase_cpu = {0, 0, 0}, phase_gpu = {0, 0, 0};
    uint32_t phase_frames = 0;
    for (const FrameStats& f : frames) {
        if (f.error_pixels >= 0) {
            s.error_measured = true;
            s.error_pixels_total += f.error_pixels;
            s.tie_pixels_total += f.tie_pixels;
            s.stray_pixels_total += std::max<int64_t>(f.stray_pixels, 0);
            s.missed_objects_total += f.missed_objects;
            s.tied_away_objects_total += f.tied_away_objects;
            s.overdrawn_objects_mean += static_cast<double>(f.overdrawn_objects);
            s.overdrawn_triangles_mean += static_cast<double>(f.overdrawn_triangles);
            if (f.error_pixels > 0) ++s.frames_with_error;
            if (f.tie_pixels > 0) ++s.frames_with_ties;
            if (f.error_pixels > s.error_pixels_worst) {
                s.error_pixels_worst = f.error_pixels;
                s.error_worst_frame = f.frame;
            }
        }
        if (f.frame < warmup_frames) continue;
        frame_ms.push_back(f.frame_ms);
        gpu_measured &= f.gpu_ms >= 0;
        gpu_ms.push_back(f.gpu_ms);
        cull += f.cull_cpu_ms;
        wait += f.wait_ms;
        update += f.update_ms;
        queries += static_cast<double>(f.queries);
        objects += static_cast<double>(f.objects_drawn);
        triangles += static_cast<double>(f.triangles);
        executed_objects += static_cast<double>(f.executed_objects);
        executed_triangles += static_cast<double>(f.executed_triangles);
        read_backs += static_cast<double>(f.read_backs);
        if (f.phase_cpu_ms[0] >= 0) {
            ++phase_frames;
            for (size_t p = 0; p < 3; ++p) {
                phase_cpu[p] += f.phase_cpu_ms[p];
                phase_gpu[p] += f.phase_gpu_ms[p];
            }
        }
    }
    if (phase_frames > 0) {
        for (size_t p = 0; p < 3; ++p) {
            s.phase_cpu_ms_mean[p] = phase_cpu[p] / phase_frames;
            s.phase_gpu_ms_mean[p] = phase_gpu[p] / phase_frames;
        }
    }
    s.timed_frames = static_cast<uint32_t>(frame_ms.size());
    s.frame_ms = distributionOf(frame_ms);
    s.frame_ms_mean_min = s.frame_ms_mean_max = s.frame_ms.mean;
    if (gpu_measured && !gpu_ms.empty()) {
        const Distribution gpu = distributionOf(gpu_ms);
        s.gpu_ms_mean = gpu.mean;
        s.gpu_ms_p95 = gpu.p95;
    }
    if (s.error_measured) {
        std::vector<double> error;
        for (const FrameStats& f : frames) error.push_back(static_cast<double>(f.error_pixels));
        std::sort(error.begin(), error.end());
        s.error_pixels_mean =
            std::accumulate(error.begin(), error.end(), 0.0) / static_cast<double>(error.size());
        const size_t rank =
            static_cast<size_t>(std::ceil(0.99 * static_cast<double>(error.size())));
        s.error_pixels_p99 = error[std::clamp<size_t>(rank, 1, error.size()) - 1];
        s.tie_pixels_mean =
            static_cast<double>(s.tie_pixels_total) / static_cast<double>(error.size());
        s.overdrawn_objects_mean /= static_cast<double>(error.size());
        s.overdrawn_triangles_mean /= static_cast<double>(error.size());
    }
    if (s.timed_frames > 0) {
        const double n = s.timed_frames;
        s.cull_cpu_ms_mean = cull / n;
        s.wait_ms_mean = wait / n;
        s.update_ms_mean = update / n;
        s.queries_mean = queries / n;
        s.objects_mean = objects / n;
        s.triangles_mean = triangles / n;
        s.executed_objects_mean = executed_objects / n;
        s.executed_triangles_mean = executed_triangles / n;
        s.read_backs_mean = read_backs / n;
    }
    summarizeShadows(frames, warmup_frames, s);
    return s;
}

}  // namespace occsim

namespace occsim {

void PoppingCounter::addFrame(const std::vector<uint8_t>& missing) {
    open_.resize(std::max(open_.size(), missing.size()), 0);
    for (size_t o = 0; o < open_.size(); ++o) {
        if (o < missing.size() && missing[o]) {
            ++open_[o];
        } else if (open_[o] > 0) {
            finished_.push_back(open_[o]);
            open_[o] = 0;
        }
    }
}

std::vector<uint32_t> PoppingCounter::runs() const {
    std::vector<uint32_t> all = finished_;
    for (uint32_t run : open_) {
        if (run > 0) all.push_back(run);
    }
    return all;
}

void addPopping(RunSummary& summary, const std::vector<uint32_t>& missing_runs) {
    summary.popping_events = static_cast<uint32_t>(missing_runs.size());
    summary.popping_max_frames = 0;
    double total = 0;
    for (uint32_t run : missing_runs) {
        total += run;
        summary.popping_max_frames = std::max(summary.popping_max_frames, run);
    }
    summary.popping_mean_frames =
        missing_runs.empty() ? 0.0 : total / static_cast<double>(missing_runs.size());
}

void addAnswerLatencies(RunSummary& summary, const std::vector<uint64_t>& histogram) {
    uint64_t total = 0;
    for (uint64_t count : histogram) total += count;
    summary.answers = total;
    if (total == 0) {
        summary.answer_latency_median = summary.answer_latency_p95 = -1;
        return;
    }
    // Nearest rank, as distributionOf() takes its p95.
    auto rankValue = [&](double fraction) {
        const uint64_t rank = std::max<uint64_t>(
            1, static_cast<uint64_t>(std::ceil(fraction * static_cast<double>(total))));
        uint64_t seen = 0;
        for (size_t k = 0; k < histogram.size(); ++k) {
            seen += histogram[k];
            if (seen >= rank) return static_cast<double>(k);
        }
        return static_cast<double>(histogram.size() - 1);
    };
    summary.answer_latency_median = rankValue(0.5);
    summary.answer_latency_p95 = rankValue(0.95);
}

double medianLatency(std::vector<uint32_t>& latencies) {
    if (latencies.empty()) return -1;
    std::sort(latencies.begin(), latencies.end());
    const size_t n = latencies.size();
    return n % 2 ? latencies[n / 2]
                 : 0.5 * (double(latencies[n / 2 - 1]) + double(latencies[n / 2]));
}

RunSummary aggregateRepetitions(const std::vector<RunSummary>& reps) {
    RunSummary out = reps.front();
    const size_t n = reps.size();
    out.repetitions = static_cast<uint32_t>(n);
    if (n == 1) return out;
    auto median = [&](auto field) {
        std::vector<double> v;
        for (const RunSummary& r : reps) v.push_back(static_cast<double>(field(r)));
        return distributionOf(v).median;
    };
    out.frame_ms.mean = median([](const RunSummary& r) { return r.frame_ms.mean; });
    out.frame_ms.median = median([](const RunSummary& r) { return r.frame_ms.median; });
    out.frame_ms.p95 = median([](const RunSummary& r) { return r.frame_ms.p95; });
    out.frame_ms.min = median([](const RunSummary& r) { return r.frame_ms.min; });
    out.frame_ms.max = median([](const RunSummary& r) { return r.frame_ms.max; });
    out.cull_cpu_ms_mean = median([](const RunSummary& r) { return r.cull_cpu_ms_mean; });
    out.wait_ms_mean = median([](const RunSummary& r) { return r.wait_ms_mean; });
    out.update_ms_mean = median([](const RunSummary& r) { return r.update_ms_mean; });
    out.queries_mean = median([](const RunSummary& r) { return r.queries_mean; });
    out.objects_mean = median([](const RunSummary& r) { return r.objects_mean; });
    out.triangles_mean = median([](const RunSummary& r) { return r.triangles_mean; });
    out.executed_objects_mean = median([](const RunSummary& r) { return r.executed_objects_mean; });
    out.executed_triangles_mean =
        median([](const RunSummary& r) { return r.executed_triangles_mean; });
    out.read_backs_mean = median([](const RunSummary& r) { return r.read_backs_mean; });
    for (size_t p = 0; p < 3; ++p) {
        out.phase_cpu_ms_mean[p] =
            median([p](const RunSummary& r) { return r.phase_cpu_ms_mean[p]; });
        out.phase_gpu_ms_mean[p] =
            median([p](const RunSummary& r) { return r.phase_gpu_ms_mean[p]; });
    }
    out.shadow_casters_mean = median([](const RunSummary& r) { return r.shadow_casters_mean; });
    out.shadow_queries_mean = median([](const RunSummary& r) { return r.shadow_queries_mean; });
    out.shadow_cpu_ms_mean = median([](const RunSummary& r) { return r.shadow_cpu_ms_mean; });
    out.shadow_gpu_ms_mean = median([](const RunSummary& r) { return r.shadow_gpu_ms_mean; });
    out.shading_cpu_ms_mean = median([](const RunSummary& r) { return r.shading_cpu_ms_mean; });
    out.shading_gpu_ms_mean = median([](const RunSummary& r) { return r.shading_gpu_ms_mean; });
    out.gpu_ms_mean = median([](const RunSummary& r) { return r.gpu_ms_mean; });
    out.gpu_ms_p95 = median([](const RunSummary& r) { return r.gpu_ms_p95; });
    out.answer_latency_median = median([](const RunSummary& r) { return r.answer_latency_median; });
    out.answer_latency_p95 = median([](const RunSummary& r) { return r.answer_latency_p95; });
    // Counts are never averaged away: a culler that misses an object in one repetition of three
    // shows the miss. Totals are sums over every repetition's frames, per-frame means are over
    // those frames, the worst frame and p99 the worst repetition's.
    out.error_pixels_total = out.missed_objects_total = out.tie_pixels_total = 0;
    out.stray_pixels_total = out.tied_away_objects_total = 0;
    out.frames_with_error = out.frames_with_ties = out.popping_events = 0;
    out.error_pixels_mean = out.tie_pixels_mean = out.error_pixels_p99 = 0;
    out.overdrawn_objects_mean = out.overdrawn_triangles_mean = 0;
    double popping_frames = 0;
    for (const RunSummary& r : reps) {
        out.error_pixels_total += r.error_pixels_total;
        out.missed_objects_total += r.missed_objects_total;
        out.tie_pixels_total += r.tie_pixels_total;
        out.stray_pixels_total += r.stray_pixels_total;
        out.tied_away_objects_total += r.tied_away_objects_total;
        out.frames_with_error += r.frames_with_error;
        out.frames_with_ties += r.frames_with_ties;
        out.popping_events += r.popping_events;
        popping_frames += r.popping_mean_frames * r.popping_events;
        // Every repetition renders the same frames: the mean over all of them is the mean of means.
        out.error_pixels_mean += r.error_pixels_mean / static_cast<double>(n);
        out.tie_pixels_mean += r.tie_pixels_mean / static_cast<double>(n);
        out.overdrawn_objects_mean += r.overdrawn_objects_mean / static_cast<double>(n);
        out.overdrawn_triangles_mean += r.overdrawn_triangles_mean / static_cast<double>(n);
        out.error_pixels_p99 = std::max(out.error_pixels_p99, r.error_pixels_p99);
    }
    out.shadow_seen_casters_mean =
        median([](const RunSummary& r) { return r.shadow_seen_casters_mean; });
    out.shadow_error_pixels_total = out.missed_casters_total = out.shadow_tie_pixels_total = -1;
    for (const RunSummary& r : reps) {
        if (r.shadow_error_pixels_total < 0) continue;
        addShadowCounts(out, r.shadow_error_pixels_total, r.missed_casters_total,
                        r.shadow_tie_pixels_total);
    }
    out.popping_mean_frames = out.popping_events ? popping_frames / out.popping_events : 0.0;
    out.frame_ms_mean_min = out.frame_ms_mean_max = reps.front().frame_ms.mean;
    for (const RunSummary& r : reps) {
        out.frame_ms_mean_min = std::min(out.frame_ms_mean_min, r.frame_ms.mean);
        out.frame_ms_mean_max = std::max(out.frame_ms_mean_max, r.frame_ms.mean);
        // The worst frame is the worst of any repetition.
        if (r.error_pixels_worst > out.error_pixels_worst) {
            out.error_pixels_worst = r.error_pixels_worst;
            out.error_worst_frame = r.error_worst_frame;
        }
        out.popping_max_frames = std::max(out.popping_max_frames, r.popping_max_frames);
    }
    return out;
}

std::vector<bool> paretoFront(const std::vector<double>& time, const std::vector<double>& error) {
    return paretoFront(time, time, error);
}

std::vector<bool> paretoFront(const std::vector<double>& time_low,
                              const std::vector<double>& time_high,
                              const std::vector<double>& error) {
    const size_t n = error.size();
    std::vector<bool> front(n, true);
    for (size_t i = 0; i < n; ++i) {
        for (size_t j = 0; j < n && front[i]; ++j) {
            // Faster only when the ranges do not overlap: a difference inside the spread is a tie.
            const bool faster = time_high[j] < time_low[i];
            const bool slower = time_high[i] < time_low[j];
            const bool no_worse = !slower && error[j] <= error[i];
            const bool better = faster || error[j] < error[i];
            if (j != i && no_worse && better) front[i] = false;
        }
    }
    return front;
}

}  // namespace occsim
