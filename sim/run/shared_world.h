// The world every configuration of a run sees: poses, movers and the BSP tree, advanced once per
// frame, with that frame's view and model-view matrices. Configurations (Simulation) render it
// through their own cullers; each culler keeps its own per-node state beside the one tree
// (NodeStateArray follows structure changes by node generation, occsim/culling/tree/node_state.h),
// so a bench of seven configurations steps the movers and refits the tree once per frame, not seven
// times. The world knows no OpenGL: ground truth of its frame is rendered by GroundTruth.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/tree/bsp_tree.h"
#include "sim/run/frame_stats.h"
#include "sim/run/frame_view.h"
#include "sim/scenario/scenario.h"
#include "sim/world/camera_path.h"
#include "sim/world/light_view.h"
#include "sim/world/world.h"

namespace occsim {

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
    // Every configuration on this world traces every frame for Simulation::lastTrace(), not only
    // SimulationOptions::trace_frame (the viewer shows one configuration at a time).
    bool trace_every_frame = false;
};

// The shadow view of a frame (docs/views.md): the scene's first shadow-casting directional light,
// its box fitted to what the camera sees this frame, and what its shadow pass needs.
struct ShadowView {
    uint32_t light = 0;     // index into Scene::lights
    uint32_t map_size = 0;  // texels a side
    LightBox box;           // empty: the camera sees none of the scene, no shadow pass this frame
    ViewSetup render;       // makeLightRenderView(box), when not empty
    CullView cull;          // makeLightCullView(box), when not empty: the light's view culled
    std::vector<glm::mat4> model_views;  // every object's, relative to the light's eye
};

class SharedWorld {
  public:
    // Builds the tree over the scene's initial poses. Throws MotionError for a non-finite
    // placement.
    SharedWorld(const Scene& scene, const Scenario& scenario);
    // Configurations hold references to it (and their cullers' state refers to its tree).
    SharedWorld(const SharedWorld&) = delete;
    SharedWorld& operator=(const SharedWorld&) = delete;

    // The next frame (frame 0 on the first call): the movers step by dt, except on frame 0 (it
    // shows the initial state) and while held; moved objects are reinserted and dirty bounds
    // refit (timed: update_ms). Then the camera is sampled at frame * dt (or the live camera)
    // and the model-view matrices are composed. Every configuration renders this frame before
    // the next advance().
    void advance();
    bool hasFrame() const { return advances_ > 0; }
    uint32_t frame() const { return frame_; }         // the current frame, once hasFrame()
    uint32_t nextFrame() const { return advances_; }  // frames advanced so far
    bool done() const { return advances_ >= scenario_.frames; }
    // Unique over every world of the process, new on every advance(): what a per-frame cache
    // (GroundTruth, a configuration's "rendered this frame") compares, so a new world that
    // happens to reuse an old one's address is never mistaken for it.
    uint64_t frameSerial() const { return serial_; }

    // The world's part of the current frame's figures (frame, time, update_ms, moved objects,
    // node changes); each configuration adds its own.
    const FrameStats& frameStats() const { return stats_; }
    // The culler's frame, without ground truth (a configuration that needs it adds it).
    const CullFrame& cullFrame() const { return cull_frame_; }
    // The camera's view. With stereo (docs/views.md) its render view draws both eyes
    // (StereoViews::render) and its culling view is the one the camera's culler culls: the
    // frustum enclosing both eyes, or the left eye's when each eye is culled on its own.
    const FrameView& view() const { return view_; }
    // The current frame's stereo views; nullptr for a scenario without stereo.
    const StereoViews* stereoViews() const { return stereo_ ? &*stereo_ : nullptr; }
    // Each eye culled on its own (StereoCulling::PerEye): the right eye needs a culler of its own.
    bool cullsEachEye() const {
        return scenario_.stereo && scenario_.stereo->culling == StereoCulling::PerEye;
    }
    std::span<const glm::mat4> modelViews() const { return model_view_; }
    // The current frame's shadow view; nullptr for a scene without a shadow-casting directional
    // light (spot lights are not rendered yet).
    const ShadowView* shadowView() const { return shadow_ ? &*shadow_ : nullptr; }
    // The scene's meshes as flat arrays (built on the first call) and the current frame's object
    // transforms into the culling frame (computed on the first call of each frame): what a culler
    // with CullerRow::needs_meshes gets in CullFrame::meshes. Runs without such a culler
    // never call it, so neither the copy nor the per-frame transforms cost them anything.
    const CullMeshes& cullMeshes();
    // What making the inscribed occluder meshes cost (on the first cullMeshes() call, outside
    // any frame's timing): meshes tried, made, and the milliseconds; per mesh refused, one line
    // naming it and why (its objects then occlude with their own mesh).
    struct OccluderMeshCost {
        uint32_t tried = 0, made = 0;
        double ms = 0.0;
        std::vector<std::string> refusals;
    };
    const OccluderMeshCost& occluderMeshCost() const { return occluder_cost_; }

    const Scene& scene() const { return scene_; }
    const Scenario& scenario() const { return scenario_; }
    const WorldState& state() const { return state_; }
    const BspTree& tree() const { return tree_; }

    // Applies from the next advance() on.
    void setLiveControls(const LiveControls& controls) { live_ = controls; }
    const LiveControls& liveControls() const { return live_; }

    // What advancing cost since construction: advance() calls (one per frame, whatever the number
    // of configurations), of which how many stepped the movers, and the update time summed.
    uint32_t advances() const { return advances_; }
    uint32_t steps() const { return steps_; }
    double updateMsTotal() const { return update_ms_total_; }

  private:
    void computeModelViews();
    void computeShadowView(const CameraPose& pose, double aspect, DepthConvention depth);

    const Scene& scene_;
    const Scenario& scenario_;
    WorldState state_;
    BspTree tree_;
    uint32_t frame_ = 0;
    uint32_t advances_ = 0;
    uint32_t steps_ = 0;
    double update_ms_total_ = 0.0;
    uint64_t serial_ = 0;
    LiveControls live_;
    FrameStats stats_;
    CullFrame cull_frame_;
    FrameView view_;
    std::optional<StereoViews> stereo_;
    std::optional<ShadowView> shadow_;
    // Per-frame scratch, reused so the steady state allocates nothing.
    std::vector<glm::mat4> model_view_;
    std::vector<uint32_t> object_triangles_;  // per object, for cullers that weigh draw costs
    // For cullers that rasterise triangles (cullMeshes()): built once, transforms per frame.
    struct FlatMeshes {
        std::vector<glm::vec3> positions;
        std::vector<uint32_t> indices;
        std::vector<MeshRange> meshes;
        std::vector<glm::mat4> object_to_culling;
        std::vector<uint8_t> object_occluder;
        std::vector<uint32_t> object_occluder_mesh;
        uint64_t transforms_serial = 0;  // the frame serial object_to_culling is for
        CullMeshes view;
    };
    static uint32_t appendCullMesh(FlatMeshes& f, const MeshData& mesh);
    std::unique_ptr<FlatMeshes> flat_meshes_;
    OccluderMeshCost occluder_cost_;
};

}  // namespace occsim
