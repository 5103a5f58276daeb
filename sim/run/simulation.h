// One configuration (an algorithm and its options) rendering a world's frames: the culler with
// its own per-node state, its devices, the measured frame, and, when asked, error against ground
// truth (popping, the worst frame) and the trace of a frame. The world itself (poses, movers, the
// BSP tree, the view) is a SharedWorld that every configuration of a run renders in lockstep, and
// ground truth of its frame is rendered once per frame by a GroundTruth they share (the
// benchmark interleaves configurations frame by frame so that machine drift hits all alike).
// A Simulation built from a scene alone owns a world and ground truth of its own.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/contract/decision_log.h"
#include "occsim/culling/devices/approximate_device.h"
#include "occsim/culling/devices/tracing_device.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/tree/bsp_tree.h"
#include "render/gl_frame_timer.h"
#include "render/gl_query_device.h"
#include "render/gl_renderer.h"
#include "sim/run/deciding_node.h"
#include "sim/run/frame_stats.h"
#include "sim/run/frame_view.h"
#include "sim/run/ground_truth.h"
#include "sim/run/pixel_error.h"
#include "sim/run/segment_tallies.h"
#include "sim/run/shared_world.h"
#include "sim/scenario/scenario.h"
#include "sim/world/receiver_mask.h"
#include "sim/world/world.h"

namespace occsim {

// Which casters a frame's shadow pass draws (docs/views.md).
enum class ShadowCasterCulling : uint8_t {
    // Every object whose box overlaps the light's box, the shadow pass before the camera's.
    LightFrustum,
    // Of those, only casters that may shadow a receiver the camera's pass drew (receiver-masked,
    // sim/world/receiver_mask.h): the camera's pass first, unshaded, then the shadow pass, then
    // a shading pass over what the camera's pass drew. Needs the drawn set on the CPU during the
    // frame: not for cullers whose draws the device decides (hzb, raster).
    ReceiverMask,
    // The configuration's culler culls the light's view too (Simulation::cullLightViewWith): an
    // instance of its own, with its own state, over the objects in the light's box, its queries
    // against the map's depth, the shadow pass before the camera's. A caster hidden from the
    // light behind other casters changes no texel of the map. Query cullers only for now: not
    // oracles, nor cullers that rasterise meshes or decide on the device.
    Culler,
    // Both, as Bittner et al. 2011 combine them: the camera's pass first and the receiver mask
    // built from it, then the light view's culler, whose draws of casters that may shadow no
    // receiver are left out (GlQueryDevice::setDrawFilter), then the shading pass.
    CullerWithReceiverMask,
};

// Whether the light's view is culled by the configuration's culler, and whether the camera's
// pass comes first for a receiver mask.
inline bool cullsLightView(ShadowCasterCulling c) {
    return c == ShadowCasterCulling::Culler || c == ShadowCasterCulling::CullerWithReceiverMask;
}
inline bool masksReceivers(ShadowCasterCulling c) {
    return c == ShadowCasterCulling::ReceiverMask ||
           c == ShadowCasterCulling::CullerWithReceiverMask;
}

// The receiver mask's resolution, texels a side.
inline constexpr uint32_t kReceiverMaskResolution = 256;

struct SimulationOptions {
    bool measure_error = false;
    ShadowCasterCulling shadow_casters = ShadowCasterCulling::LightFrustum;
    LatencyMode latency;
    // Keep the frame with the most error pixels (culled colour and IDs, ground-truth colour and
    // IDs) for a picture of what went wrong. Costs a colour read-back per frame; regression
    // runs turn it on.
    bool keep_worst_error_frame = false;
    // Record this frame's draws and queries (for the bird's-eye picture); see lastTrace(). The
    // recording sits inside that frame's timing (a vector append per draw or query).
    std::optional<uint32_t> trace_frame;
    // Time the culled render on the GPU (GL_TIME_ELAPSED): only where the figure means
    // something (ContextInfo::gpu_time_meaningful; not on llvmpipe).
    bool measure_gpu_time = false;
    // Keep every object's decision, its reason and its pixels of each frame (objectFrames(), for
    // objects.sqlite): the culler's decision log is on (its appends sit inside the frame's
    // timing), everything else is worked out after the frame. Needs measure_error.
    bool record_objects = false;
    // The run's segments: popping and answer latencies are also counted per segment
    // (segmentTallies()).
    std::vector<Segment> segments;
    // The clock the measured frame is timed with (frame_ms and the culler's CPU time), in
    // milliseconds from any fixed point; empty: the steady clock. Tests script it, so that a
    // check on frame times sees the same times whatever else the machine is doing.
    std::function<double()> frame_clock_ms;
};

// One object's part of a frame (SimulationOptions::record_objects).
struct ObjectFrame {
    Decision why;        // the culler's reason (occsim/culling/contract/decision_log.h)
    bool drawn = false;  // the device drew it (a conditional draw: it executed)
    ObjectPixels pixels;
    // The node whose record decided it (the tree's node index this frame), when one did.
    DecidingNode node_kind = DecidingNode::None;
    uint32_t node = 0;
};

// The frame of a run with the most error pixels, as read back (rows bottom-up, as GL gives them),
// with each pixel's PixelDifference (sim/run/pixel_error.h) so that a picture can tell errors
// from ties.
// What a culler did with an object in a frame, beside ground truth (error measured): what the
// viewer's validation overlay shows.
enum class ObjectVerdict : uint8_t {
    DrawnVisible,  // drawn, and ground truth sees it
    Missed,        // ground truth sees it, not drawn
    DrawnHidden,   // drawn while ground truth does not see it (over-draw)
    Culled,        // not drawn, not seen
};

struct ErrorFrame {
    uint32_t frame = 0;
    int64_t error_pixels = 0;
    int64_t tie_pixels = 0;
    std::vector<uint8_t> culled_rgba, truth_rgba;
    std::vector<uint32_t> culled_ids, truth_ids;
    std::vector<uint8_t> differences;  // PixelDifference per pixel
};

class Simulation {
  public:
    // A configuration on a world it shares with others: the caller advances the world once per
    // frame and has every configuration render that frame. The world and ground truth must
    // outlive the simulation. The renderer must have the scene's meshes uploaded (uploadScene()).
    // `options` are the culler's (its approximation knobs apply when the algorithm issues
    // queries). The culler starts with fresh per-node state on the world as it is now, so a
    // configuration can join a world in the middle of its frames (the viewer switching algorithm).
    Simulation(SharedWorld& world, GroundTruth& truth, const CullerRow& algorithm,
               std::unique_ptr<Culler> culler, const CullerOptions& options, GlRenderer& renderer,
               const SimulationOptions& sim_options);
    // A configuration alone, on a world and ground truth of its own that renderFrame() advances.
    Simulation(const Scene& scene, const Scenario& scenario, const CullerRow& algorithm,
               std::unique_ptr<Culler> culler, const CullerOptions& options, GlRenderer& renderer,
               const SimulationOptions& sim_options);

    ~Simulation();

    // ShadowCasterCulling::Culler: the culler of the light's view, an instance of the
    // configuration's own culler made for it (its state apart from the camera's). Throws
    // RegistryError, one line, for a culler that cannot cull a light's view yet.
    void cullLightViewWith(std::unique_ptr<Culler> culler);
    // Stereo culled per eye (SharedWorld::cullsEachEye): the right eye's culler, an instance of the
    // configuration's own made for it; the configuration's culler culls the left eye.
    void cullRightEyeWith(std::unique_ptr<Culler> culler);

    bool needsGroundTruth() const;
    // Renders the world's current frame through the culler and measures it (ground truth, when
    // needed, comes from the shared GroundTruth, outside the timing). On a shared world, once
    // per advance(): a second call for the same frame throws std::logic_error. A simulation
    // that owns its world advances it first.
    FrameStats renderFrame();

    bool keepsWorstErrorFrame() const { return options_.keep_worst_error_frame; }
    // Empty (error_pixels 0) until a frame with error was seen.
    const ErrorFrame& worstErrorFrame() const { return worst_; }
    // Popping: for every object that was visible in ground truth and not drawn, how many
    // consecutive frames it stayed missing (runs still open at the end are included).
    std::vector<uint32_t> poppingRuns() const { return popping_.runs(); }
    // The answer latencies of the frames after the scenario's warm-up, as counts per latency
    // (addAnswerLatencies()).
    const std::vector<uint64_t>& answerLatencies() const { return answer_latencies_; }
    // Culled object-ID and depth buffers read back to count error (none unless error is measured).
    uint64_t errorReadBacks() const { return error_read_backs_; }
    // Popping and answer latencies per segment of SimulationOptions::segments.
    const SegmentTallies& segmentTallies() const { return segment_tallies_; }
    // Per object, the last frame measured against ground truth (ObjectVerdict values); empty
    // before one, or when error is not measured.
    const std::vector<uint8_t>& objectVerdicts() const { return verdicts_; }
    // The trace of options.trace_frame (or of every frame, LiveControls::trace_every_frame) once
    // that frame was rendered; null before. The tree, the world and view() stay as the culler
    // saw them until the world's next advance().
    const FrameTrace* lastTrace() const { return traced_ ? &tracer_.trace() : nullptr; }
    // Per object, the last frame rendered (SimulationOptions::record_objects; empty otherwise).
    // In a stereo run culled per eye, the left eye's: its pass's decisions, the pixels of its half.
    const std::vector<ObjectFrame>& objectFrames() const { return object_frames_; }
    // The right eye's, in a stereo run culled per eye (its own culler's decisions, the pixels of
    // its half); empty otherwise.
    const std::vector<ObjectFrame>& rightEyeObjectFrames() const {
        return right_eye_object_frames_;
    }
    // The same for the light's view, when the culler culls it (cullsLightView) and the frame had a
    // shadow pass; empty otherwise. `pixels.truth` is the visible pixels ground truth shadows
    // through the caster (GroundTruthFrame::shadow_pixels), `pixels.error` those of them it left
    // lit by not being drawn (all of them when it was not drawn, else none), `pixels.tie` 0.
    const std::vector<ObjectFrame>& lightObjectFrames() const { return light_object_frames_; }
    // The scene's light whose view lightObjectFrames() are of.
    uint32_t recordedLight() const;

    SharedWorld& world() { return *world_; }
    const SharedWorld& world() const { return *world_; }
    const FrameView& view() const { return world_->view(); }
    const BspTree& tree() const { return world_->tree(); }
    const WorldState& state() const { return world_->state(); }
    const CullerRow& algorithm() const { return algorithm_; }
    const Culler& culler() const { return *culler_; }

  private:
    Simulation(std::unique_ptr<SharedWorld> own_world, std::unique_ptr<GroundTruth> own_truth,
               SharedWorld* world, GroundTruth* truth, const CullerRow& algorithm,
               std::unique_ptr<Culler> culler, const CullerOptions& options, GlRenderer& renderer,
               const SimulationOptions& sim_options);
    void renderShadowPass(const ShadowView& shadow, const CullFrame& camera, FrameStats& stats);
    void resolveLightViewCasters();
    void selectCasters(const ShadowView& shadow);
    void buildReceiverMask(const ShadowView& shadow);
    void shadeCameraPass(FrameStats& stats);
    void measureShadowError(const GroundTruthFrame& truth, FrameStats& stats);
    void measureError(const GroundTruthFrame& truth, FrameStats& stats);
    void recordObjects(const GroundTruthFrame& truth);
    void recordLightObjects(const GroundTruthFrame& truth);
    void recordAnswerLatencies(uint32_t frame, FrameStats& stats);
    double nowMs() const;  // SimulationOptions::frame_clock_ms, else the steady clock

    std::unique_ptr<SharedWorld> own_world_;  // only for a simulation alone
    std::unique_ptr<GroundTruth> own_truth_;
    SharedWorld* world_;
    GroundTruth* truth_;
    const CullerRow& algorithm_;
    std::unique_ptr<Culler> culler_;
    GlRenderer& renderer_;
    SimulationOptions options_;
    // The culler's device: the GL device, wrapped by the approximation when it is active, and
    // by the tracer on the traced frame. device_ is the outermost of the first two.
    GlQueryDevice gl_device_;
    std::unique_ptr<ApproximateDevice> approximate_device_;
    RenderDevice* device_;
    TracingDevice tracer_;
    bool traced_ = false;
    uint64_t rendered_serial_ = 0;  // the world's frameSerial() last rendered; 0: none
    uint64_t error_read_backs_ = 0;
    // Per-frame scratch, reused so the steady state allocates nothing.
    ErrorFrame worst_;
    std::vector<uint8_t> missing_;   // per object, this frame: visible in ground truth, not drawn
    std::vector<uint8_t> verdicts_;  // per object, this frame: an ObjectVerdict
    PoppingCounter popping_;
    SegmentTallies segment_tallies_;
    std::unique_ptr<GlFrameTimer> gpu_timer_;  // when options_.measure_gpu_time
    // The shadow pass (SharedWorld::shadowView): this configuration's own map, made on its first
    // pass, the casters it drew this frame (per object) and their timer.
    std::unique_ptr<GlShadowMap> shadow_map_;
    ShadowLookup shadow_lookup_;  // this frame's, for the camera's pass and the receivers' margin
    std::unique_ptr<GlFrameTimer> shadow_gpu_timer_;
    std::unique_ptr<GlFrameTimer> shading_gpu_timer_;  // receiver-masked
    std::vector<uint32_t> shadow_casters_;
    std::vector<uint8_t> cast_shadow_;
    // A view culled by an instance of its own, on devices of its own (as device_'s): the light's
    // (cullsLightView) and the right eye's (stereo per eye).
    struct ViewCulling;
    std::unique_ptr<ViewCulling> light_;
    std::unique_ptr<ViewCulling> right_eye_;
    std::unique_ptr<ViewCulling> makeViewCulling(std::unique_ptr<Culler> culler);
    void reserveDecisions(DecisionLog& log) const;
    // Eye `eye`'s half of a read-back of this frame's stereo framebuffer (stereoEyePixels).
    template <class T>
    std::span<T> eyePixels(std::span<T> pixels, int eye) const {
        return stereoEyePixels(pixels, eye, renderer_.width(), renderer_.height());
    }
    void cullRightEye(const CullFrame& camera);
    void splitEyeTruth(const GroundTruthFrame& truth);
    ApproximationOptions approximation_;
    ReceiverMask receiver_mask_;                // masksReceivers()
    std::vector<uint8_t> may_shadow_;           // per object: the mask's draw filter (light view)
    std::vector<uint8_t> camera_submitted_;     // per object: the camera's pass drew it
    std::vector<uint8_t> right_eye_submitted_;  // stereo per eye: the right eye's pass drew it
    std::vector<uint32_t> camera_depth_;        // the camera pass's depth, for the receivers
    std::vector<uint32_t> culled_shadow_texels_;
    std::vector<float> truth_shadow_depth_, culled_shadow_depth_;  // on a frame with a difference
    std::vector<uint32_t> frame_latencies_;
    std::vector<uint32_t> right_latencies_;  // stereo per eye: the right eye's device's
    // Stereo per eye with an oracle: what ground truth shows each eye (0/1 per object).
    std::vector<uint8_t> left_truth_visible_, right_truth_visible_;
    std::vector<uint64_t> answer_latencies_;
    std::vector<uint32_t> culled_ids_;
    std::vector<uint32_t> culled_depth_;
    std::vector<uint8_t> culled_visible_;
    // record_objects: the culler's log, and what it and the pixels say per object.
    DecisionLog decisions_;
    std::vector<Decision> reasons_;
    std::vector<QueryTag> reason_subjects_;
    std::vector<uint32_t> resolve_stack_;
    std::vector<uint8_t> marks_;
    std::vector<ObjectPixels> object_pixels_;
    std::vector<ObjectFrame> object_frames_;
    // record_objects in stereo per eye: the right eye's.
    std::vector<Decision> right_eye_reasons_;
    std::vector<QueryTag> right_eye_subjects_;
    std::vector<ObjectPixels> right_eye_pixels_;
    std::vector<ObjectFrame> right_eye_object_frames_;
    // record_objects with a culled light view: the same for it.
    std::vector<Decision> light_reasons_;
    std::vector<QueryTag> light_subjects_;
    std::vector<ObjectFrame> light_object_frames_;
};

// What the views of a run do not take yet (docs/views.md): a culler that cannot cull a light's
// view or a stereo view, receiver masking with a culler whose draws the device decides. Throws
// RegistryError, one line; a run checks every configuration before frame 0 and before it says
// anything of its views.
void requireViewSupport(const CullerRow& algorithm, const Scenario& scenario,
                        ShadowCasterCulling shadow_casters);

// Uploads the scene's meshes and object-to-mesh table to the renderer (once per scene).
void uploadScene(const Scene& scene, GlRenderer& renderer);

}  // namespace occsim
