// Synthetic frames for the tests of a run's figures (segments, worst windows, moments): frames
// with given times and objects drawn, segments, a culler with a planted slow window beside Ideal,
// and a run's record of them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "sim/run/frame_stats.h"
#include "sim/run/results.h"
#include "sim/scenario/scenario.h"

namespace occsim::testing {

// `count` frames from 0, frame f taking ms(f) and drawing objects(f) objects of 100 triangles.
template <class Ms, class Objects>
inline std::vector<FrameStats> frames(uint32_t count, Ms ms, Objects objects) {
    std::vector<FrameStats> out(count);
    for (uint32_t f = 0; f < count; ++f) {
        out[f].frame = f;
        out[f].time_s = f / 30.0;
        out[f].frame_ms = ms(f);
        out[f].objects_drawn = objects(f);
        out[f].triangles = 100 * out[f].objects_drawn;
        out[f].queries = f % 3;
        out[f].error_pixels = f == 6 ? 40 : 0;
        out[f].tie_pixels = 0;
        out[f].stray_pixels = 0;
        out[f].missed_objects = f == 6 ? 2 : 0;
        out[f].tied_away_objects = 0;
        out[f].visible_objects = 5;
    }
    return out;
}

inline Segment segment(const std::string& name, uint32_t first, uint32_t end) {
    Segment s;
    s.name = name;
    s.first_frame = first;
    s.end_frame = end;
    s.origin = "scenario";
    return s;
}

// Ideal at 2 ms; the culler at 2 ms except a planted window (frames 40 to 49 at 6 ms, frame 44 at
// 9 ms) and a smaller bump (frames 70 to 74 at 4 ms).
inline std::vector<FrameStats> plantedCuller() {
    return frames(
        100,
        [](uint32_t f) {
            if (f == 44) return 9.0;
            if (f >= 40 && f < 50) return 6.0;
            if (f >= 70 && f < 75) return 4.0;
            return 2.0;
        },
        [](uint32_t f) { return f >= 40 && f < 50 ? 30 : 5; });
}

inline std::vector<FrameStats> idealFrames() {
    return frames(
        100, [](uint32_t) { return 2.0; }, [](uint32_t) { return 3; });
}

inline RunRecord record(const char* algorithm, std::vector<FrameStats> f) {
    RunRecord r;
    r.algorithm = findCuller(algorithm);
    r.frames = std::move(f);
    r.summary = summarize(algorithm, r.frames, 10);
    return r;
}

}  // namespace occsim::testing
