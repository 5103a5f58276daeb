#include "sim/frame_stats.h"

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

RunSummary summarize(const std::string& algorithm, const std::vector<FrameStats>& frames,
                     uint32_t warmup_frames) {
    RunSummary s;
    s.algorithm = algorithm;
    s.frames = static_cast<uint32_t>(frames.size());
    std::vector<double> frame_ms;
    double cull = 0, wait = 0, update = 0, queries = 0, objects = 0, triangles = 0;
    for (const FrameStats& f : frames) {
        if (f.error_pixels >= 0) {
            s.error_measured = true;
            s.error_pixels_total += f.error_pixels;
            s.missed_objects_total += f.missed_objects;
            if (f.error_pixels > 0) ++s.frames_with_error;
            if (f.error_pixels > s.error_pixels_worst) {
                s.error_pixels_worst = f.error_pixels;
                s.error_worst_frame = f.frame;
            }
        }
        if (f.frame < warmup_frames) continue;
        frame_ms.push_back(f.frame_ms);
        cull += f.cull_cpu_ms;
        wait += f.wait_ms;
        update += f.update_ms;
        queries += static_cast<double>(f.queries);
        objects += static_cast<double>(f.objects_drawn);
        triangles += static_cast<double>(f.triangles);
    }
    s.timed_frames = static_cast<uint32_t>(frame_ms.size());
    s.frame_ms = distributionOf(frame_ms);
    if (s.timed_frames > 0) {
        const double n = s.timed_frames;
        s.cull_cpu_ms_mean = cull / n;
        s.wait_ms_mean = wait / n;
        s.update_ms_mean = update / n;
        s.queries_mean = queries / n;
        s.objects_mean = objects / n;
        s.triangles_mean = triangles / n;
    }
    return s;
}

}  // namespace occsim
