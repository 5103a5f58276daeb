// The moments where a culler lost most: per configuration, the windows of kWorstWindowFrames
// consecutive timed frames where its frame time over the reference's is highest (the reference is
// Ideal when it ran, VFC otherwise), each with the figures that explain it. Found after every run,
// unasked, from the frames alone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/run/frame_stats.h"

namespace occsim {

struct RunRecord;

// A third of a second at 30 frames a second: short enough to be one moment (a camera turn, a
// mover passing), long enough that one slow frame alone (a scheduler hiccup) moves the window's
// ratio by a tenth of its own.
inline constexpr uint32_t kWorstWindowFrames = 10;
inline constexpr size_t kWorstWindowsPerConfiguration = 3;

struct WorstWindow {
    uint32_t first_frame = 0;
    uint32_t frames = 0;  // the window is [first_frame, first_frame + frames)
    // Sum of the configuration's frame times over the window / the reference's.
    double ratio = 0.0;
    double frame_ms_mean = 0.0, reference_frame_ms_mean = 0.0;
    // The window's frame with the highest frame time over the reference's (the first on ties).
    uint32_t worst_frame = 0;
    double worst_frame_ms = 0.0, worst_reference_frame_ms = 0.0;
    // Means per frame over the window, the configuration's and the reference's.
    double objects_mean = 0.0, reference_objects_mean = 0.0;
    double triangles_mean = 0.0, reference_triangles_mean = 0.0;
    double queries_mean = 0.0, wait_ms_mean = 0.0;
    // Summed over the window; -1 when error was not measured.
    int64_t error_pixels = -1, missed_objects = -1;
};

// Up to `count` windows of `window` consecutive frames at or after warmup_frames (all of them when
// fewer are timed), none overlapping, where Σ frames' frame_ms / Σ reference's is highest, worst
// first; the first on ties. Frame i of one is frame i of the other (the same run); a window whose
// reference took no time is skipped.
std::vector<WorstWindow> findWorstWindows(const std::vector<FrameStats>& frames,
                                          const std::vector<FrameStats>& reference,
                                          uint32_t warmup_frames,
                                          uint32_t window = kWorstWindowFrames,
                                          size_t count = kWorstWindowsPerConfiguration);

// A configuration's frames with every figure the median over its repetitions, frame by frame
// (the first repetition's frames when it ran once).
std::vector<FrameStats> medianFrames(const RunRecord& record);

// The run windows are measured against: the Ideal oracle (unswept first), else the speedup
// reference (VFC); -1 when neither ran.
int windowReference(const std::vector<RunRecord>& runs);

// Fills RunRecord::worst_windows of every configuration but the reference and the oracles, over
// medianFrames(), and none when nothing was in view on any frame (nothingInView); returns
// windowReference(runs).
int markWorstWindows(std::vector<RunRecord>& runs, uint32_t warmup_frames);

}  // namespace occsim
