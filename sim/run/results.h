// What a benchmark returns: per configuration its frames and summaries, the run's metadata (built
// once, read by the console, summary.json and report.md alike), and the worst error frames.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "sim/run/frame_stats.h"
#include "sim/run/run_config.h"
#include "sim/run/simulation.h"
#include "sim/run/worst_windows.h"
#include "sim/scenario/segments.h"
#include "sim/scenario/view_specs.h"

namespace occsim {

// One configuration's runs. summary.label holds the configuration's label (the algorithm
// name, or "name knob=value" in a sweep); with repetitions, summary is the median over them.
struct RunRecord {
    RunSummary summary;
    std::vector<FrameStats> frames;  // first repetition
    std::vector<std::vector<FrameStats>> later_repetitions;
    std::vector<RunSummary> repetitions;   // one per repetition
    const CullerRow* algorithm = nullptr;  // the culler
    // What the culler was configured with: every option after defaults, sweeps and --culling
    // (summary.json records them), and the shared approximation knobs.
    OptionValues options;
    ApproximationOptions approximation;
    std::string culling_file;             // RunConfig::culling_file
    std::optional<CostModel> cost_model;  // the one it read, when it weighs costs
    bool pareto = false;                  // on the time-against-error front
    // Per segment of RunMetadata::segments: the summary over its frames, over the repetitions
    // as `summary` is (aggregateRepetitions()), and each repetition's.
    std::vector<RunSummary> segments;
    std::vector<std::vector<RunSummary>> segment_repetitions;  // [segment][repetition]
    // Where it lost most against BenchResult::window_reference (empty for the reference itself,
    // for oracles, and when no reference ran).
    std::vector<WorstWindow> worst_windows;
};

// Everything about a run that is not a measurement: what ran, how, and where.
struct RunMetadata {
    std::string command = "bench";  // the command that ran it: run, bench, regress, tune
    std::string command_line;       // as typed
    // The scenario.
    std::string scenario_name;
    std::string scenario_file;
    std::string scenario_id;  // its identity in a regression run (scenario_identity.h); else empty
    uint32_t frames = 0;
    uint32_t warmup_frames = 0;
    double dt_s = 0.0;
    uint64_t seed = 0;
    uint32_t objects = 0;
    uint64_t triangles = 0;
    uint32_t movers = 0;
    // occluderRolesText() of the scene when a configuration has an occluder pass (needs_meshes);
    // else empty.
    std::string occluder_roles;
    // The configurations that rendered in a GL context of their own (sim/run/config_contexts.h).
    std::vector<std::string> contexts_apart;
    // The run.
    uint32_t repetitions = 1;
    std::string frame_order = "balanced";  // sim/run/frame_order.h
    bool error_measured = false;
    std::optional<uint32_t> deterministic_latency;  // commands, when the mode was on
    std::optional<Sweep> sweep;
    // The cost model the cullers that weigh costs were given (statistical+), and where it came
    // from: "scenario", "calibrated" (measured before the first frame) or "reference".
    std::optional<CostModel> cost_model;
    std::string cost_model_source;
    // The machine.
    uint32_t hardware_threads = 0;
    // The load average (1, 5 and 15 minutes) when the run started and when it ended: a run on a
    // machine busier than its hardware threads measured the other work too. Negative: unknown.
    std::array<double, 3> load_before{-1.0, -1.0, -1.0};
    std::array<double, 3> load_after{-1.0, -1.0, -1.0};
    // Other work beside the run: the 1-minute load before it above the hardware threads, or after
    // it above twice that (the run's own threads count in the figure after it).
    bool busyMachine() const;
    std::string lp_num_threads = "default";  // LP_NUM_THREADS as set, or "default"
    std::string heap = "kept";               // keepFreedMemory() (sim/run/heap_policy.h)
    std::string renderer;                    // "GL_RENDERER, OpenGL GL_VERSION"
    // The headless context (render/headless_context.h): which backend and device made it, and
    // what it says it is.
    std::string backend;             // "egl" or "osmesa"
    std::optional<uint32_t> device;  // the EGL device index
    std::string gl_vendor, gl_renderer, gl_version, driver;
    bool gpu_time_meaningful = false;  // false on software rasterisers (llvmpipe)
    std::string backend_fallback;      // why --backend auto took OSMesa; empty when it did not
    uint32_t width = 0, height = 0;    // a view's (each eye's with stereo)
    // The scenario's stereo (docs/views.md), when it has one: two eyes a frame.
    std::optional<StereoSpec> stereo;
    std::string depth_format;  // the depth buffer both renders share: what a tie's step is
    // The run's segments (BenchOptions::segments), frames as it ran them.
    std::vector<Segment> segments;
};

// The run's own work beside the frames it measured, over every repetition: what a reader needs to
// see that no work hides outside the frame times.
struct RunCosts {
    // The frame loops, from the first frame's advance() to the last frame's end: set-up (scene,
    // context, uploads, calibration, building each repetition's world) excluded; the world's
    // update, ground truth, error counting and the on_frame hook (pictures) included.
    double wall_ms = 0.0;
    double frame_ms_total = 0.0;  // every configuration's frames, warm-up included
    // The shared world: advanced once per frame whatever the number of configurations.
    uint32_t world_advances = 0;
    uint32_t world_steps = 0;            // advances that stepped the movers
    double world_update_ms_total = 0.0;  // movers, reinsertion and refit
    // Ground truth: rendered at most once per frame, and only when error is measured or an
    // oracle runs; render and read-back time, outside every frame timing.
    uint32_t ground_truth_renders = 0;
    double ground_truth_ms_total = 0.0;
    uint64_t error_read_backs = 0;  // culled object-ID buffers read to count error
    // After the frames: the world replayed to the worst windows' worst frames for their pictures
    // (BenchOptions::on_window_frame); 0 when none was asked for.
    uint32_t window_frames_replayed = 0;
    double window_replay_ms = 0.0;
    // Inscribed occluder meshes (sim/scene/occluder_mesh.h) for a culler that rasterises
    // occluders (masked): scene meshes tried and made, and the time, once per repetition's world
    // before its first culled frame, outside every frame timing; 0 when no culler needs meshes.
    uint32_t occluder_meshes_tried = 0;
    uint32_t occluder_meshes_made = 0;
    double occluder_meshes_ms = 0.0;
};

// A run that ended before its last frame: stopped by a signal (SIGINT, SIGTERM), or by a
// configuration whose frame failed (a culler that threw). The whole frames before it are kept and
// reported; the writers mark every output partial with partialLine().
struct PartialRun {
    std::string reason;           // "interrupted by SIGINT", "configuration 'x' failed: ..."
    int signal = 0;               // the signal that asked to stop; 0 when a configuration failed
    uint32_t repetition = 0;      // the repetition it ended in, from 0
    uint32_t frames_reached = 0;  // whole frames of that repetition, done by every configuration
};

struct BenchResult {
    RunMetadata metadata;
    RunCosts costs;
    std::vector<RunRecord> runs;
    std::vector<ErrorFrame> worst_error_frames;  // per run, when keep_worst_error_frame
    std::optional<PartialRun> partial;           // set when the run ended early
    // The label of the run worst windows are measured against (Ideal, else VFC); empty: none ran.
    std::string window_reference;
};

// "partial: interrupted by SIGINT after 12 of 40 frames; the 12 whole frames are reported", or
// with repetitions, which whole repetitions are; empty for a complete run.
std::string partialLine(const BenchResult& result);

// "EGL device 0" or "OSMesa": where the run rendered, for the console and reports.
std::string backendLabel(const RunMetadata& m);

// True when no configuration drew an object on any frame and ground truth (where rendered) saw
// none: the camera looks at nothing, so frame-time ratios compare empty frames.
bool nothingInView(const std::vector<RunRecord>& runs);

// Speedup over the reference (its mean / this mean) and ratio to the oracle (this mean / the
// oracle's mean); 0 when that algorithm is not among the runs, or when nothingInView(runs).
double speedupOverReference(const std::vector<RunRecord>& runs, const RunSummary& s);
double ratioToOracle(const std::vector<RunRecord>& runs, const RunSummary& s);

// Marks RunRecord::pareto over every run that is not an oracle (the bound is no candidate): the
// front of mean frame time against error pixels per frame, where with repetitions two times whose
// spreads overlap tie (paretoFront()).
void markParetoFront(std::vector<RunRecord>& runs);

}  // namespace occsim
