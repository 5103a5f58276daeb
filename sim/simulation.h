// One algorithm's run over a scenario's frames: step the movers (simulation time), reinsert the
// moved objects into the BSP tree, render the frame through the culler and measure it, and, when
// asked, render ground truth (VFC into the object-ID buffer) outside the timing to count error.
// Several Simulations can share one GlRenderer and step in lockstep (the benchmark interleaves
// algorithms frame by frame so that machine drift hits all alike).
#pragma once

#include "culling/bsp_tree.h"
#include "culling/culler.h"
#include "render/gl_query_device.h"
#include "render/gl_renderer.h"
#include "sim/frame_stats.h"
#include "sim/scenario.h"
#include "sim/world.h"

#include <memory>
#include <vector>

namespace occsim {

struct SimulationOptions {
    bool measure_error = false;
    LatencyMode latency;
};

// The view of one frame: everything a culler and the renderer need from the camera.
struct FrameView {
    CullView cull;
    ViewSetup render;
};

FrameView makeFrameView(const CameraSpec& camera, double time_s, uint32_t width, uint32_t height);

class Simulation {
public:
    // The renderer must have the scene's meshes uploaded (uploadScene()).
    Simulation(const Scene& scene, const Scenario& scenario, std::unique_ptr<Culler> culler,
               GlRenderer& renderer, const SimulationOptions& options);

    // Renders the next frame and returns its figures. Call while !done().
    FrameStats step();
    bool done() const { return frame_ >= scenario_.frames; }
    uint32_t frame() const { return frame_; }

    const Culler& culler() const { return *culler_; }
    const BspTree& tree() const { return tree_; }
    const WorldState& state() const { return state_; }

private:
    void prepareView(const FrameView& view);
    void renderGroundTruth(const CullFrame& frame);

    const Scene& scene_;
    const Scenario& scenario_;
    std::unique_ptr<Culler> culler_;
    std::unique_ptr<Culler> ground_truth_culler_;
    GlRenderer& renderer_;
    SimulationOptions options_;
    GlQueryDevice device_;
    GlQueryDevice ground_truth_device_;
    WorldState state_;
    BspTree tree_;
    uint32_t frame_ = 0;
    // Per-frame scratch, reused so the steady state allocates nothing.
    std::vector<glm::mat4> model_view_;
    std::vector<uint32_t> ground_truth_ids_;
    std::vector<uint32_t> culled_ids_;
    std::vector<uint8_t> ground_truth_visible_;
    std::vector<uint8_t> culled_visible_;
};

// Uploads the scene's meshes and object-to-mesh table to the renderer (once per scene).
void uploadScene(const Scene& scene, GlRenderer& renderer);

}  // namespace occsim
