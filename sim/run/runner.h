// Running a scenario with one or more configurations, interleaved frame by frame, and returning
// what was measured. Nothing here writes a file: pictures are taken by the caller's on_frame hook
// (sim/output/pictures.h) and the tables and reports are written from the result afterwards
// (sim/output/run_outputs.h).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "render/headless_context.h"
#include "sim/run/frame_order.h"
#include "sim/run/progress.h"
#include "sim/run/results.h"
#include "sim/run/run_config.h"
#include "sim/run/simulation.h"
#include "sim/run/verdict_log.h"
#include "sim/scenario/scenario.h"

namespace occsim {

// A configuration's frame has just been rendered (outside every timing): the hook may read the
// simulation and the renderer's buffers, e.g. to save a picture of it.
struct FrameEvent {
    uint32_t repetition = 0;
    uint32_t frame = 0;
    const RunConfig& config;
    const Simulation& simulation;
    const Scenario& scenario;
    GlRenderer& renderer;
};

// What the verdict logs of all a run's configurations may hold together (BenchOptions::
// on_window_frame): the teapots' 120 frames of 12 configurations keep about 8 MB.
inline constexpr size_t kVerdictLogBudgetBytes = size_t{256} << 20;

// A configuration whose worst window's worst frame a replayed frame is, with what it missed and
// drew while hidden on that frame in the first repetition, for its picture's validation overlay.
struct WindowVerdicts {
    std::string label;                        // the configuration's
    const FrameVerdicts* verdicts = nullptr;  // null: not kept, or error not measured
    bool measured = false;                    // error was measured (null verdicts: over budget)
};

// A frame of the run rendered again after it (BenchOptions::on_window_frame): the world replayed
// to it and drawn whole, every object with no culling code (ground truth's colour: what the camera
// saw), outside every timing. Rows bottom-up, as GL gives them.
struct ReplayedFrame {
    uint32_t frame = 0;
    double time_s = 0.0;  // frame * dt: seconds of the camera path
    const std::vector<uint8_t>& rgba;
    uint32_t width = 0, height = 0;
    // Ground truth's object IDs (index + 1, 0 background), rows bottom-up as the colour; the
    // world's boxes at this frame (culling frame); the frame's camera and near plane.
    std::span<const uint32_t> truth_ids;
    std::span<const Aabb> object_boxes;
    ViewSetup view;
    double near_m = 0.1;
    std::vector<WindowVerdicts> windows;  // in the order of the runs
};

struct BenchOptions {
    std::vector<const CullerRow*> algorithms;  // from cullerRows(); at least one
    // Which casters a shadow pass draws (docs/views.md), every configuration alike.
    ShadowCasterCulling shadow_casters = ShadowCasterCulling::LightFrustum;
    // Explicit configurations (label, algorithm, options), e.g. a tuner's samples beside its
    // reference; when given, `algorithms` and `sweep` are not used. Labels must differ.
    std::vector<RunConfig> configs;
    bool measure_error = false;
    LatencyMode latency;
    BackendChoice backend;           // --backend, --device
    std::optional<uint32_t> frames;  // overrides the scenario's frame count
    std::string command = "bench";   // recorded in the metadata
    std::string command_line;        // recorded in the metadata
    std::string scenario_id;         // a regression run's id of the scenario (metadata)
    ProgressStyle progress = ProgressStyle::None;  // on stderr (sim/run/progress.h)
    bool keep_worst_error_frame = false;           // see SimulationOptions; needs measure_error
    // Every object's decision, reason and pixels per frame of the first repetition, for on_frame
    // to read (Simulation::objectFrames(); SimulationOptions::record_objects); needs
    // measure_error.
    bool record_objects = false;
    uint32_t repetitions = 1;  // each configuration runs this often; medians reported
    // The order each frame renders the configurations in (sim/run/frame_order.h). A place has
    // its own cost (the first renders right after ground truth, each other right after the one
    // before it, which may have left work behind): balanced spreads both over every
    // configuration; fixed lands them on the same configurations every frame.
    FrameOrder frame_order = FrameOrder::balanced;
    std::optional<Sweep> sweep;  // one configuration per value (run_config.h)
    std::string ablate;          // an algorithm to run with each mechanism off (run_config.h)
    // Record this frame's draws and queries for every configuration (first repetition), so that
    // on_frame can picture its culling decisions (Simulation::lastTrace()).
    std::optional<uint32_t> trace_frame;
    std::function<void(const FrameEvent&)> on_frame;
    // Segments (sim/scenario/segments.h, planSegments()): every summary is also made over each.
    std::vector<Segment> segments;
    // After the last repetition (not after a run that a signal stopped): each frame that is the
    // worst frame of a configuration's worst window (RunRecord::worst_windows), in frame order,
    // replayed and handed here, e.g. to save its picture. The world replays the same frames as
    // every repetition did, so the frame is the one measured; its cost is RunCosts::window_*.
    // With error measured, each configuration's verdicts of every frame of the first repetition
    // are kept for it (VerdictLog, at most kVerdictLogBudgetBytes for all of them).
    std::function<void(const ReplayedFrame&)> on_window_frame;
    // Makes the culler for an algorithm; default makeCuller(). Tests inject broken ones.
    std::function<std::unique_ptr<Culler>(const CullerRow&, const CullerOptions&)> make_culler;
    // The clock frames are timed with (SimulationOptions::frame_clock_ms); empty: the steady
    // clock. Tests script it.
    std::function<double()> frame_clock_ms;
    // The scene warnings a session of several runs (the tuner's batches) has printed: a warning
    // already in it is not printed again, and each one printed is added. Without it (nullptr)
    // every run prints its scene's warnings.
    std::set<std::string>* warnings_shown = nullptr;
    // A note for the person running it (a scene's occluder mesh refused, ...), without "note: "
    // and without a newline; empty: "note: <line>" on stderr as it is. The commands wrap it to
    // the terminal's 100 columns (sim/output/console_table.h, a layer above).
    std::function<void(const std::string&)> on_note;
};

// A run ends early, with the whole frames before it and BenchResult::partial set, when a stop
// was requested (sim/run/stop_request.h: after the frame in hand) or a configuration's frame
// threw (the frames before it; the error is named in partial, not thrown). The frame loop notes
// the configuration in hand for the crash handler (sim/run/crash_note.h).
// Throws BackendUnavailable when the backend or device asked for cannot serve (bad input),
// std::runtime_error on rendering failures, std::invalid_argument for a sweep value that
// makes an algorithm's options invalid, and the scene builder's errors (ScenarioError, GltfError).
BenchResult runBenchmark(const Scenario& scenario, const BenchOptions& options);

}  // namespace occsim
