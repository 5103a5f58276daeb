// One algorithm's run over a scenario's frames: step the movers (simulation time), reinsert the
// moved objects into the BSP tree, render the frame through the culler and measure it, and, when
// asked, render ground truth outside the timing to count error.
// Several Simulations can share one GlRenderer and step in lockstep (the benchmark interleaves
// algorithms frame by frame so that machine drift hits all alike).
#pragma once

#include "culling/algorithms.h"
#include "culling/approximate_device.h"
#include "culling/bsp_tree.h"
#include "culling/culler.h"
#include "culling/tracing_device.h"
#include "render/gl_query_device.h"
#include "render/gl_renderer.h"
#include "sim/run/frame_stats.h"
#include "sim/scenario/scenario.h"
#include "sim/world/camera_path.h"
#include "sim/world/world.h"

#include <memory>
#include <optional>
#include <vector>

namespace occsim {

struct SimulationOptions {
    bool measure_error = false;
    LatencyMode latency;
    // Keep the frame with the most error pixels (culled colour and IDs, ground-truth colour and
    // IDs) for a picture of what went wrong. Costs a colour read-back per frame; regression
    // runs turn it on.
    bool keep_worst_error_frame = false;
    // Record this frame's draws and queries (for the bird's-eye picture); see lastTrace(). The
    // recording sits inside that frame's timing (a vector append per draw or query).
    std::optional<uint32_t> trace_frame;
};

// The view of one frame: everything a culler and the renderer need from the camera.
struct FrameView {
    CullView cull;
    ViewSetup render;
};

// The camera of one frame. The culling view (eye, frustum) is relative to `culling_origin`
// (Scene::culling_origin), like the object boxes and the tree; the render view is in world
// coordinates.
FrameView makeFrameView(const CameraSpec& camera, double time_s, uint32_t width, uint32_t height,
                        const glm::dvec3& culling_origin,
                        DepthConvention depth = DepthConvention::ReverseFloat);
// The same for a given pose; `camera` supplies the lens (field of view, near and far planes).
FrameView makeFrameView(const CameraSpec& camera, const CameraPose& pose, uint32_t width,
                        uint32_t height, const glm::dvec3& culling_origin,
                        DepthConvention depth = DepthConvention::ReverseFloat);

// The renderer's depth convention a scenario asks for.
DepthConvention depthConventionOf(const Scenario& scenario);

// What an interactive viewer (sim/view/) changes between frames; run, bench and regress never
// set these, and the defaults change nothing.
struct LiveControls {
    // The camera of the coming frames, instead of the scenario's path at frame * dt.
    std::optional<CameraPose> camera;
    // The viewport the view is set up for, when the renderer was resized to it (0: the
    // scenario's).
    uint32_t width = 0, height = 0;
    // The movers hold still (a paused viewer still renders frames as the camera moves). The
    // frame count and the culler's time go on: cullers expect a new frame index every frame.
    bool hold_world = false;
    // Trace every frame for lastTrace(), not only SimulationOptions::trace_frame.
    bool trace_every_frame = false;
};

// Ground truth of one frame: every object drawn (the GPU clips, no culling code involved) into
// the object-ID buffer, read back, and which objects it saw.
struct GroundTruthFrame {
    std::vector<uint32_t> ids;     // width * height, object index + 1, 0 = background
    std::vector<uint8_t> visible;  // per object
    std::vector<uint8_t> rgba;     // colour, only when some simulation keeps its worst frame
};

// The frame of a run with the most error pixels, as read back (rows bottom-up, as GL gives them).
struct ErrorFrame {
    uint32_t frame = 0;
    int64_t error_pixels = 0;
    std::vector<uint8_t> culled_rgba, truth_rgba;
    std::vector<uint32_t> culled_ids, truth_ids;
};

class Simulation {
public:
    // The renderer must have the scene's meshes uploaded (uploadScene()). `options` are the
    // culler's (its approximation knobs apply when the algorithm issues queries).
    Simulation(const Scene& scene, const Scenario& scenario, const AlgorithmTraits& algorithm,
               std::unique_ptr<Culler> culler, const CullerOptions& options, GlRenderer& renderer,
               const SimulationOptions& sim_options);

    // A frame in two halves, so that simulations running in lockstep over the same world can
    // share one ground-truth render per frame: advance() moves the world and sets up the view;
    // renderFrame() renders (and measures) it. With `shared` null the simulation renders its own
    // ground truth when it needs one.
    void advance();
    bool needsGroundTruth() const;
    // For the current (advanced) frame; with_colour also reads back its colour buffer.
    const GroundTruthFrame& renderGroundTruth(bool with_colour = false);
    FrameStats renderFrame(const GroundTruthFrame* shared);

    bool done() const { return frame_ >= scenario_.frames; }
    bool keepsWorstErrorFrame() const { return options_.keep_worst_error_frame; }
    // Empty (error_pixels 0) until a frame with error was seen.
    const ErrorFrame& worstErrorFrame() const { return worst_; }
    // Popping: for every object that was visible in ground truth but not drawn, how many
    // consecutive frames it stayed missing (runs still open at the end are included).
    std::vector<uint32_t> poppingRuns() const { return popping_.runs(); }
    uint32_t frame() const { return frame_; }
    // The trace of options.trace_frame once that frame was rendered; null before. The tree, the
    // world and view() stay as the culler saw them until the next advance().
    const FrameTrace* lastTrace() const { return traced_ ? &tracer_.trace() : nullptr; }
    const FrameView& view() const { return view_; }

    // Applies from the next advance() on.
    void setLiveControls(const LiveControls& controls) { live_ = controls; }
    // Takes over the world of `other` (poses, movers, tree and frame count) between two of its
    // frames, so that a viewer can switch the algorithm, or turn error measurement on, without
    // restarting the world. This simulation's culler starts with fresh per-node state.
    void continueFrom(const Simulation& other);

    const AlgorithmTraits& algorithm() const { return algorithm_; }
    const Culler& culler() const { return *culler_; }
    const BspTree& tree() const { return tree_; }
    const WorldState& state() const { return state_; }

private:
    void computeModelViews();  // for view_ and the current poses
    void measureError(const GroundTruthFrame& truth, FrameStats& stats);

    const Scene& scene_;
    const Scenario& scenario_;
    const AlgorithmTraits& algorithm_;
    std::unique_ptr<Culler> culler_;
    GlRenderer& renderer_;
    SimulationOptions options_;
    // The culler's device: the GL device, wrapped by the approximation when it is active, and
    // by the tracer on the traced frame. device_ is the outermost of the first two.
    GlQueryDevice gl_device_;
    GlQueryDevice ground_truth_device_;
    std::unique_ptr<ApproximateDevice> approximate_device_;
    RenderDevice* device_;
    TracingDevice tracer_;
    bool traced_ = false;
    WorldState state_;
    BspTree tree_;
    uint32_t frame_ = 0;
    bool advanced_ = false;     // advance() ran for frame_, renderFrame() not yet
    FrameStats pending_;        // the figures advance() gathered for frame_
    CullFrame cull_frame_;
    FrameView view_;
    // Per-frame scratch, reused so the steady state allocates nothing.
    std::vector<glm::mat4> model_view_;
    std::vector<uint32_t> object_triangles_;  // per object, for cullers that weigh draw costs
    GroundTruthFrame ground_truth_;
    ErrorFrame worst_;
    std::vector<uint8_t> missing_;  // per object, this frame: visible in ground truth, not drawn
    PoppingCounter popping_;
    std::vector<uint32_t> culled_ids_;
    std::vector<uint8_t> culled_visible_;
    LiveControls live_;
};

// Uploads the scene's meshes and object-to-mesh table to the renderer (once per scene).
void uploadScene(const Scene& scene, GlRenderer& renderer);

}  // namespace occsim
