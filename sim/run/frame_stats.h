// What one frame of one algorithm cost and how wrong it was, and the summary over a run.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace occsim {

struct FrameStats {
    uint32_t frame = 0;
    double time_s = 0.0;  // simulation time
    // Wall clock: frame start to glFinish, the culled render only (with a shadow pass, it too).
    double frame_ms = 0.0;
    double cull_cpu_ms = 0.0;  // culler's own CPU time (traversal minus submission and waits)
    double wait_ms = 0.0;      // blocked on query results
    double update_ms = 0.0;    // movers, BSP reinsertion and refit (outside frame_ms)
    // GL_TIME_ELAPSED around the culled camera pass (not the shadow pass: shadow_gpu_ms); -1 when
    // not measured (a software rasteriser, whose timer queries do not time rasterisation:
    // ContextInfo::gpu_time_meaningful).
    double gpu_ms = -1.0;
    // Query answers that became ready this frame, and the median of their latencies: commands
    // (draws and queries) submitted after a query by the time its answer was ready (-1: none).
    uint64_t answers = 0;
    double answer_latency_median = -1.0;
    uint64_t queries = 0;
    uint64_t objects_drawn = 0;  // submitted draws, and their triangles
    uint64_t triangles = 0;
    // Of those, what the device executed: all of them but conditional draws it skipped on their
    // query's result (render/gl_query_device.h: counted with GL_PRIMITIVES_GENERATED).
    uint64_t executed_objects = 0;
    uint64_t executed_triangles = 0;
    // Reads of device results during the frame (query answers, pyramid flags): each makes the
    // CPU wait for the device's work so far. GPU-driven cullers make none (DeviceCounters).
    uint64_t read_backs = 0;
    // GPU-driven cullers (hzb, raster): milliseconds of phase 1, the test and phase 2, submission
    // on the CPU and between timestamps on the GPU (render/gl_gpu_driven_draws.h; on a software
    // rasteriser the "GPU" times are its threads' CPU time); -1 for other cullers.
    std::array<double, 3> phase_cpu_ms = {-1.0, -1.0, -1.0};
    std::array<double, 3> phase_gpu_ms = {-1.0, -1.0, -1.0};
    // The shadow pass (docs/views.md), -1 on a frame without one: casters drawn into the light's
    // shadow map and their triangles, its CPU time from the pass's start to the camera pass's
    // (submission and light-frustum culling), and its GL_TIME_ELAPSED (-1 where GPU time is not
    // measured, as gpu_ms).
    int64_t shadow_casters = -1;
    int64_t shadow_triangles = -1;
    // The light view's occlusion queries, when the configuration's culler culls it
    // (--shadow-casters culler, culler+receivers); 0 in a shadow pass without, -1 without one.
    int64_t shadow_queries = -1;
    double shadow_cpu_ms = -1.0;
    double shadow_gpu_ms = -1.0;
    // Receiver-masked caster culling's shading pass (the camera's objects drawn again with the
    // shadow term): its CPU time and GL_TIME_ELAPSED, -1 without one (GPU: as gpu_ms).
    double shading_cpu_ms = -1.0;
    double shading_gpu_ms = -1.0;
    uint64_t moved_objects = 0;
    uint64_t node_changes = 0;  // reinsertions that moved an object to another BSP node
    // Error against ground truth (docs/error.md); -1 when error was not measured.
    int64_t error_pixels = -1;    // ground truth shows a nearer surface than the culled frame
    int64_t tie_pixels = -1;      // another object at the same depth (draw order): no error
    int64_t stray_pixels = -1;    // ground truth's stray fragments the culled frame lacks: no error
    int64_t missed_objects = -1;  // seen by ground truth, not drawn by the culler
    // Seen by ground truth and drawn, yet without a pixel in the culled frame: every one of its
    // pixels went to a tie (what "missed" counted when it was judged by IDs alone). Named
    // drawn_unseen_objects before; no file read back holds it.
    int64_t tied_away_objects = -1;
    int64_t visible_objects = -1;  // objects with at least one pixel in ground truth
    // Over-draw: objects the culler drew that ground truth does not see (no pixel of theirs in
    // the full render), and their triangles: the work culling was there to save.
    int64_t overdrawn_objects = -1;
    int64_t overdrawn_triangles = -1;
    // Stereo with error measured (-1 otherwise): error_pixels of each eye's half of the frame (the
    // two add up to error_pixels).
    int64_t left_error_pixels = -1;
    int64_t right_error_pixels = -1;
    // Error of the shadow term, with a shadow pass and error measured (-1 otherwise): pixels
    // showing the same object as ground truth but lit where it is shadowed or the other way
    // round, and casters whose shadow ground truth shows on a visible pixel but the shadow pass
    // did not draw.
    int64_t shadow_error_pixels = -1;
    int64_t missed_casters = -1;
    // Pixels whose lit state differs only because a caster one depth step from ground truth's
    // stands in for it in the map (sim/run/shadow_error.h): no error.
    int64_t shadow_tie_pixels = -1;
    // Casters whose shadow ground truth shows on a visible pixel: what a perfect caster culler
    // would draw (-1 as above).
    int64_t shadow_seen_casters = -1;
};

struct Distribution {
    double mean = 0, median = 0, p95 = 0, min = 0, max = 0;
};

Distribution distributionOf(std::vector<double> values);

struct RunSummary {
    // The configuration's label: the algorithm name, or "name knob=value" in a sweep.
    std::string label;
    uint32_t frames = 0;        // all frames
    uint32_t timed_frames = 0;  // frames after warm-up, over which timing figures are taken
    Distribution frame_ms;
    double cull_cpu_ms_mean = 0, wait_ms_mean = 0, update_ms_mean = 0;
    // Over the timed frames; -1 when GPU time was not measured (see FrameStats::gpu_ms).
    double gpu_ms_mean = -1, gpu_ms_p95 = -1;
    // Every answer of the timed frames (addAnswerLatencies): median and p95 of its latency in
    // commands; -1 when no query was answered.
    uint64_t answers = 0;
    double answer_latency_median = -1, answer_latency_p95 = -1;
    double queries_mean = 0, objects_mean = 0, triangles_mean = 0;
    double executed_objects_mean = 0, executed_triangles_mean = 0;  // over the timed frames
    double read_backs_mean = 0;                                     // over the timed frames
    // Means over the timed frames of FrameStats::phase_cpu_ms and phase_gpu_ms; -1 when no timed
    // frame measured them.
    std::array<double, 3> phase_cpu_ms_mean = {-1.0, -1.0, -1.0};
    std::array<double, 3> phase_gpu_ms_mean = {-1.0, -1.0, -1.0};
    // Over the timed frames with a shadow pass (FrameStats::shadow_*); -1 when none had one, or
    // (GPU) none measured it.
    double shadow_casters_mean = -1, shadow_cpu_ms_mean = -1, shadow_gpu_ms_mean = -1;
    double shadow_queries_mean = -1;  // the light view's occlusion queries (0: no culler there)
    double shading_cpu_ms_mean = -1, shading_gpu_ms_mean = -1;  // receiver-masked only
    // Over every frame with a shadow pass and error measured; -1 when there was none.
    int64_t shadow_error_pixels_total = -1, missed_casters_total = -1, shadow_tie_pixels_total = -1;
    double shadow_seen_casters_mean = -1;
    bool error_measured = false;
    int64_t error_pixels_total = 0;
    int64_t error_pixels_worst = 0;
    uint32_t error_worst_frame = 0;
    uint32_t frames_with_error = 0;
    int64_t tie_pixels_total = 0;
    uint32_t frames_with_ties = 0;
    double tie_pixels_mean = 0;  // per frame, over all frames
    int64_t stray_pixels_total = 0;
    int64_t missed_objects_total = 0;
    int64_t tied_away_objects_total = 0;
    // Over-draw per frame, over all frames (FrameStats::overdrawn_objects).
    double overdrawn_objects_mean = 0, overdrawn_triangles_mean = 0;
    double error_pixels_mean = 0;  // per frame, over all frames
    double error_pixels_p99 = 0;   // per frame, nearest rank
    // Popping: runs of consecutive frames in which an object visible in ground truth was not
    // drawn (one run per object and disappearance; a tie is no disappearance).
    uint32_t popping_events = 0;
    double popping_mean_frames = 0;
    uint32_t popping_max_frames = 0;
    // Over repetitions (all equal to frame_ms.mean for a single run). With repetitions, `frames`
    // and `timed_frames` are one repetition's; the error counts above are over all of them.
    uint32_t repetitions = 1;
    double frame_ms_mean_min = 0, frame_ms_mean_max = 0;
};

RunSummary summarize(const std::string& label, const std::vector<FrameStats>& frames,
                     uint32_t warmup_frames);

// Counts popping: per object, runs of consecutive frames in which it was visible in ground truth
// but not drawn. Feed it one frame at a time.
class PoppingCounter {
  public:
    // missing[o] != 0 when object o was visible in ground truth and not drawn this frame.
    void addFrame(const std::vector<uint8_t>& missing);
    // Lengths of every run, finished or still open.
    std::vector<uint32_t> runs() const;

  private:
    std::vector<uint32_t> open_;  // per object: length of its current run
    std::vector<uint32_t> finished_;
};

// Fills the popping figures from the lengths of the missing runs.
void addPopping(RunSummary& summary, const std::vector<uint32_t>& missing_runs);

// Counts of answer latencies: histogram[k] answers had k commands submitted after their query
// by the time they were ready (Simulation::answerLatencies()).
void addAnswerLatencies(RunSummary& summary, const std::vector<uint64_t>& histogram);

// Median of the latencies a frame's answers had (-1 when there were none); sorts `latencies`.
double medianLatency(std::vector<uint32_t>& latencies);

// One summary for several repetitions of the same configuration (docs/cli.md "Repetitions"):
// timings and the per-frame means of queries, objects and triangles are medians over the
// repetitions (frame_ms_mean_min/max give the spread of the mean frame time); counts of error
// (error, tie and stray pixels, missed and tied-away objects, frames with error or ties, popping
// events) are sums over every repetition's frames, never averaged; per-frame error means are
// over those frames; the worst frame, p99 and the longest popping run the worst repetition's.
RunSummary aggregateRepetitions(const std::vector<RunSummary>& repetitions);

// Indices of the points on the Pareto front of (time, error), both to be minimised: no other
// point is at least as good in both and better in one.
std::vector<bool> paretoFront(const std::vector<double>& time, const std::vector<double>& error);
// The same with each time a range (the spread of repetitions, low to high): a point is faster
// only when its whole range lies below the other's; overlapping ranges tie on time.
std::vector<bool> paretoFront(const std::vector<double>& time_low,
                              const std::vector<double>& time_high,
                              const std::vector<double>& error);

}  // namespace occsim
