#include "sim/run/simulation.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "occsim/culling/tree/decision_resolution.h"
#include "sim/run/shadow_error.h"
#include "sim/run/visible_receivers.h"

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

// The node whose record decided an object (its reason's subject), when one did.
void setDecidingNode(const BspTree& tree, const QueryTag& subject, ObjectFrame& f) {
    f.node_kind = DecidingNode::None;
    f.node = 0;
    if (subject.subject != QueryTag::Subject::Object && subject.index < tree.nodeCount()) {
        f.node = subject.index;
        f.node_kind = tree.node(subject.index).isLeaf()            ? DecidingNode::Leaf
                      : subject.subject == QueryTag::Subject::Node ? DecidingNode::Subtree
                                                                   : DecidingNode::NodeObjects;
    }
}

// One camera view's record per object (the camera's, or an eye's): its culler's reasons resolved
// on the tree and their subjects, what its device drew, and its pixels.
void fillObjectFrames(const BspTree& tree, const std::vector<Decision>& reasons,
                      const std::vector<QueryTag>& subjects, const GlQueryDevice& device,
                      const std::vector<ObjectPixels>& pixels, uint32_t objects,
                      std::vector<ObjectFrame>& out) {
    out.resize(objects);
    for (uint32_t o = 0; o < objects; ++o) {
        ObjectFrame& f = out[o];
        f.why = o < reasons.size() ? reasons[o] : Decision{};
        f.drawn = device.drew(o);
        f.pixels = pixels[o];
        setDecidingNode(tree, o < subjects.size() ? subjects[o] : QueryTag{}, f);
    }
}

}  // namespace

// A view's culler on a device of its own (the light's, the right eye's): its queries, drawn set
// and counters apart from the camera's, wrapped by the approximation as the camera's device is.
struct Simulation::ViewCulling {
    ViewCulling(std::unique_ptr<Culler> c, GlRenderer& renderer, const LatencyMode& latency,
                const ApproximationOptions* approximation)
        : culler(std::move(c)),
          gl_device(renderer, latency),
          approximate(approximation ? std::make_unique<ApproximateDevice>(gl_device, *approximation)
                                    : nullptr),
          device(approximate ? static_cast<RenderDevice*>(approximate.get()) : &gl_device) {}

    std::unique_ptr<Culler> culler;
    GlQueryDevice gl_device;
    std::unique_ptr<ApproximateDevice> approximate;
    RenderDevice* device;
    DecisionLog decisions;  // SimulationOptions::record_objects
};

Simulation::~Simulation() = default;

void uploadScene(const Scene& scene, GlRenderer& renderer) {
    renderer.uploadMeshes(scene.meshes);
    renderer.setObjectMeshes(scene.object_mesh);
}

Simulation::Simulation(SharedWorld& world, GroundTruth& truth, const CullerRow& algorithm,
                       std::unique_ptr<Culler> culler, const CullerOptions& options,
                       GlRenderer& renderer, const SimulationOptions& sim_options)
    : Simulation(nullptr, nullptr, &world, &truth, algorithm, std::move(culler), options, renderer,
                 sim_options) {}

Simulation::Simulation(const Scene& scene, const Scenario& scenario, const CullerRow& algorithm,
                       std::unique_ptr<Culler> culler, const CullerOptions& options,
                       GlRenderer& renderer, const SimulationOptions& sim_options)
    : Simulation(std::make_unique<SharedWorld>(scene, scenario),
                 std::make_unique<GroundTruth>(renderer), nullptr, nullptr, algorithm,
                 std::move(culler), options, renderer, sim_options) {}

Simulation::Simulation(std::unique_ptr<SharedWorld> own_world,
                       std::unique_ptr<GroundTruth> own_truth, SharedWorld* world,
                       GroundTruth* truth, const CullerRow& algorithm,
                       std::unique_ptr<Culler> culler, const CullerOptions& options,
                       GlRenderer& renderer, const SimulationOptions& sim_options)
    : own_world_(std::move(own_world)),
      own_truth_(std::move(own_truth)),
      world_(own_world_ ? own_world_.get() : world),
      truth_(own_truth_ ? own_truth_.get() : truth),
      algorithm_(algorithm),
      culler_(std::move(culler)),
      renderer_(renderer),
      options_(sim_options),
      gl_device_(renderer, sim_options.latency),
      approximate_device_(
          algorithm.issues_queries && options.approximation.active()
              ? std::make_unique<ApproximateDevice>(gl_device_, options.approximation)
              : nullptr),
      device_(approximate_device_ ? static_cast<RenderDevice*>(approximate_device_.get())
                                  : &gl_device_),
      tracer_(*device_),
      approximation_(options.approximation) {
    // Before any frame: a culler that needs what this device lacks is refused with one line.
    requireDeviceFeatures(algorithm_, device_->features());
    requireViewSupport(algorithm_, world_->scenario(), options_.shadow_casters);
    if (options_.record_objects && !options_.measure_error) {
        throw std::logic_error("Simulation: record_objects needs measure_error");
    }
    if (options_.record_objects) reserveDecisions(decisions_);
    if (options_.measure_gpu_time) gpu_timer_ = std::make_unique<GlFrameTimer>();
    segment_tallies_.reset(options_.segments, world_->scenario().warmup_frames);
    culler_->reset(world_->tree());
}

void requireViewSupport(const CullerRow& algorithm, const Scenario& scenario,
                        ShadowCasterCulling shadow_casters) {
    if (shadow_casters == ShadowCasterCulling::ReceiverMask &&
        (algorithm.device_needs & kGpuDrivenDraws) != 0) {
        throw RegistryError(
            "culler '" + algorithm.name +
            "' draws from the device (its drawn set is not on the CPU during the "
            "frame): receiver-masked shadow culling does not take it yet; leave it out of "
            "--algos");
    }
    if (cullsLightView(shadow_casters)) {
        const char* why = algorithm.oracle ? "it decides from the camera's ground truth"
                          : (algorithm.device_needs & (kGpuDrivenDraws | kDepthPyramid)) != 0
                              ? "its decisions are taken on the device against the camera's depth"
                              : nullptr;
        if (why != nullptr) {
            throw RegistryError("culler '" + algorithm.name + "' cannot cull a light's view yet (" +
                                why +
                                "): leave it out of --algos, or use --shadow-casters frustum");
        }
    }
    if (!scenario.stereo) return;
    const bool per_eye = scenario.stereo->culling == StereoCulling::PerEye;
    if ((algorithm.device_needs & (kGpuDrivenDraws | kDepthPyramid)) != 0) {
        throw RegistryError("culler '" + algorithm.name +
                            "' cannot cull a stereo view yet (its decisions are taken on the "
                            "device against one view's depth): leave it out of --algos");
    }
    // A software depth buffer is one eye's: per eye each eye has its own.
    if (algorithm.needs_meshes && !per_eye) {
        throw RegistryError("culler '" + algorithm.name +
                            "' cannot cull a stereo view in one enclosing pass (it rasterises "
                            "one eye's depth itself): use \"culling\": \"per_eye\" (--stereo "
                            "SEPARATION,per_eye), or leave it out of --algos");
    }
}

// A record or two per node and object a frame: room enough that a frame allocates nothing.
void Simulation::reserveDecisions(DecisionLog& log) const {
    log.reserve(4 * (size_t{world_->tree().nodeCount()} + world_->tree().objectCount()));
}

std::unique_ptr<Simulation::ViewCulling> Simulation::makeViewCulling(
    std::unique_ptr<Culler> culler) {
    const bool approximate = algorithm_.issues_queries && approximation_.active();
    auto view = std::make_unique<ViewCulling>(std::move(culler), renderer_, options_.latency,
                                              approximate ? &approximation_ : nullptr);
    view->culler->reset(world_->tree());
    if (options_.record_objects) reserveDecisions(view->decisions);
    return view;
}

void Simulation::cullLightViewWith(std::unique_ptr<Culler> culler) {
    if (!cullsLightView(options_.shadow_casters)) {
        throw std::logic_error("Simulation::cullLightViewWith: the shadow casters are not culled");
    }
    light_ = makeViewCulling(std::move(culler));
    if (masksReceivers(options_.shadow_casters)) {
        // The paper's hierarchical test: a query on a node whose box may shadow no receiver the
        // camera sees counts no sample, so the culler culls the node with its subtree. The mask
        // is this frame's: built before the light's view is culled (receivers first).
        light_->gl_device.setQueryFilter([this](const Aabb& box) {
            return receiver_mask_.mayShadow(box, world_->scene().culling_origin);
        });
    }
}

void Simulation::cullRightEyeWith(std::unique_ptr<Culler> culler) {
    if (!world_->cullsEachEye()) {
        throw std::logic_error("Simulation::cullRightEyeWith: the eyes are not culled apart");
    }
    right_eye_ = makeViewCulling(std::move(culler));
}

uint32_t Simulation::recordedLight() const {
    const ShadowView* shadow = world_->shadowView();
    return shadow != nullptr ? shadow->light : 0;
}

double Simulation::nowMs() const {
    if (options_.frame_clock_ms) return options_.frame_clock_ms();
    return std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count();
}

bool Simulation::needsGroundTruth() const { return options_.measure_error || algorithm_.oracle; }

FrameStats Simulation::renderFrame() {
    const bool fresh = world_->hasFrame() && rendered_serial_ != world_->frameSerial();
    if (!fresh) {
        if (!own_world_) {
            throw std::logic_error(
                "Simulation::renderFrame: the shared world has no new frame (advance it first)");
        }
        world_->advance();
    }
    rendered_serial_ = world_->frameSerial();
    if (cullsLightView(options_.shadow_casters) && !light_) {
        throw std::logic_error("Simulation::renderFrame: the light's view has no culler");
    }
    if (world_->cullsEachEye() && !right_eye_) {
        throw std::logic_error("Simulation::renderFrame: the right eye has no culler");
    }
    FrameStats stats = world_->frameStats();
    CullFrame cull_frame = world_->cullFrame();
    const uint32_t frame = world_->frame();

    // Ground truth, outside the timing, when error is measured or the culler is the oracle; one
    // render per frame serves every configuration that asks.
    const GroundTruthFrame* truth = nullptr;
    if (needsGroundTruth()) {
        truth = &truth_->of(*world_, options_.keep_worst_error_frame);
        cull_frame.ground_truth_visible = truth->visible;
        if (right_eye_ && algorithm_.oracle) {
            // Per eye, each eye's oracle decides from what ground truth shows that eye alone.
            splitEyeTruth(*truth);
            cull_frame.ground_truth_visible = left_truth_visible_;
        }
    }
    // The meshes and this frame's transforms, outside the timing (an engine keeps its transforms
    // anyway), for a culler that rasterises triangles itself.
    if (algorithm_.needs_meshes) cull_frame.meshes = world_->cullMeshes();
    if (options_.record_objects) {
        decisions_.clear();
        cull_frame.decisions = &decisions_;
    }

    // The measured frame: the shadow pass, if any, then the culled camera pass, to glFinish.
    // With a shadow pass the camera's matrices are uploaded inside the frame, after it (the
    // light's take the same buffer).
    const ShadowView* shadow = world_->shadowView();
    const bool shadow_pass = shadow != nullptr && !shadow->box.empty;
    if (!shadow_pass) renderer_.setView(world_->view().render, world_->modelViews());
    if (shadow_pass && (!shadow_map_ || shadow_map_->size() != shadow->map_size)) {
        shadow_map_ = std::make_unique<GlShadowMap>(shadow->map_size);  // outside the timing
    }
    // How the camera's pass looks the map up this frame (the views' matrices, as setView's).
    if (shadow_pass) {
        shadow_lookup_ = shadow_map_->lookupFor(world_->view().render, shadow->render,
                                                renderer_.depthConvention());
    }
    if (shadow_pass && options_.measure_gpu_time && !shadow_gpu_timer_) {
        shadow_gpu_timer_ = std::make_unique<GlFrameTimer>();
        if (masksReceivers(options_.shadow_casters)) {
            shading_gpu_timer_ = std::make_unique<GlFrameTimer>();
        }
    }
    device_->resetCounters();
    gl_device_.beginDrawnSet(world_->scene().objectCount());
    const double frame_start = nowMs();
    const bool receivers_first = shadow_pass && masksReceivers(options_.shadow_casters);
    if (shadow_pass && !receivers_first) {
        renderShadowPass(*shadow, cull_frame, stats);
        renderer_.setView(world_->view().render, world_->modelViews());
        renderer_.setShadow(&shadow_lookup_);
    } else if (receivers_first) {
        renderer_.setView(world_->view().render, world_->modelViews());
    }
    if (gpu_timer_) gpu_timer_->begin();
    renderer_.beginFrame();
    const double cull_start = nowMs();
    const bool trace = world_->liveControls().trace_every_frame ||
                       (options_.trace_frame && *options_.trace_frame == frame);
    if (trace) tracer_.beginTrace(frame);
    if (right_eye_) renderer_.setEyes(StereoEyes::Left);
    culler_->cullAndRender(world_->tree(), cull_frame, trace ? tracer_ : *device_);
    tracer_.endTrace();
    traced_ |= trace;
    if (right_eye_) cullRightEye(cull_frame);
    const double cull_ms = nowMs() - cull_start;
    if (gpu_timer_) gpu_timer_->end();
    if (receivers_first) {
        // The receivers are what the camera's pass drew: the shadow pass draws the casters they
        // may catch the shadow of, then the camera's pass is shaded from the map.
        gl_device_.markSubmitted(camera_submitted_);
        if (right_eye_) right_eye_->gl_device.markSubmitted(right_eye_submitted_);
        renderShadowPass(*shadow, cull_frame, stats);
        shadeCameraPass(stats);
    }
    renderer_.finish();
    stats.frame_ms = nowMs() - frame_start;
    if (gpu_timer_) stats.gpu_ms = gpu_timer_->resultMs();
    recordAnswerLatencies(frame, stats);
    // Outside the timing: what GPU-driven draws drew (read back from their command lists), then
    // the culler's own look at the device's decisions, for its decision log.
    const uint64_t read_backs_in_frame = device_->counters().read_backs;
    gl_device_.resolveGpuDrivenDraws();
    if (trace) tracer_.addDeviceDecidedDraws(gl_device_.gpuDrivenDrawnObjects());
    if (const auto* phases = gl_device_.gpuDrivenPhaseTimes()) {
        for (size_t p = 0; p < 3; ++p) {
            stats.phase_cpu_ms[p] = phases->cpu_ms[p];
            stats.phase_gpu_ms[p] = phases->gpu_ms[p];
        }
    }
    culler_->afterFrame(*device_);
    if (shadow_pass && light_) resolveLightViewCasters();

    DeviceCounters c = device_->counters();
    uint64_t read_backs = read_backs_in_frame;
    // What the device skipped of the conditional draws, read back after the frame.
    GlQueryDevice::SkippedDraws skipped = gl_device_.skippedConditionalDraws();
    if (right_eye_) {
        // Stereo per eye: the frame's figures are both eyes' passes together.
        right_eye_->culler->afterFrame(*right_eye_->device);
        const DeviceCounters& r = right_eye_->device->counters();
        read_backs += r.read_backs;
        c.submit_seconds += r.submit_seconds;
        c.wait_seconds += r.wait_seconds;
        c.poll_seconds += r.poll_seconds;
        c.queries_issued += r.queries_issued;
        c.objects_drawn += r.objects_drawn;
        c.triangles_drawn += r.triangles_drawn;
        const GlQueryDevice::SkippedDraws right = right_eye_->gl_device.skippedConditionalDraws();
        skipped.objects += right.objects;
        skipped.triangles += right.triangles;
    }
    stats.read_backs = read_backs;
    stats.wait_ms = c.wait_seconds * 1e3;
    // The culler's own work: its time minus every device call (draws, queries, polls, waits).
    stats.cull_cpu_ms =
        std::max(0.0, cull_ms - (c.submit_seconds + c.wait_seconds + c.poll_seconds) * 1e3);
    stats.queries = c.queries_issued;
    stats.objects_drawn = c.objects_drawn;
    stats.triangles = c.triangles_drawn;
    stats.executed_objects = c.objects_drawn - skipped.objects;
    stats.executed_triangles = c.triangles_drawn - skipped.triangles;

    if (options_.measure_error) measureError(*truth, stats);
    if (shadow_pass) {
        if (shadow_gpu_timer_) stats.shadow_gpu_ms = shadow_gpu_timer_->resultMs();
        if (shading_gpu_timer_ && receivers_first) {
            stats.shading_gpu_ms = shading_gpu_timer_->resultMs();
        }
        renderer_.setShadow(nullptr);
    }
    return stats;
}

// The casters selectCasters() keeps, drawn into the map (docs/views.md), or those the light
// view's culler draws. Timed from the pass's start (caster selection, the light's matrices
// uploaded) to its last draw's submission (with a culler, its last query's answer it waited for).
void Simulation::renderShadowPass(const ShadowView& shadow, const CullFrame& camera,
                                  FrameStats& stats) {
    const double start = nowMs();
    if (!light_) {
        selectCasters(shadow);
    } else if (masksReceivers(options_.shadow_casters)) {
        // The light view's culler decides; the casters that may shadow no receiver are left out
        // of its draws.
        buildReceiverMask(shadow);
        const std::vector<Aabb>& boxes = world_->state().boxes;
        const glm::dvec3& origin = world_->scene().culling_origin;
        may_shadow_.resize(boxes.size());
        for (size_t o = 0; o < boxes.size(); ++o) {
            may_shadow_[o] = receiver_mask_.mayShadow(boxes[o], origin) ? 1 : 0;
        }
        light_->gl_device.setDrawFilter(may_shadow_);
    }
    renderer_.setView(shadow.render, shadow.model_views);
    if (shadow_gpu_timer_) shadow_gpu_timer_->begin();
    shadow_map_->begin(renderer_);
    const uint32_t objects = world_->scene().objectCount();
    if (light_) {
        CullFrame frame;
        frame.frame_index = camera.frame_index;
        frame.time_s = camera.time_s;
        frame.view = shadow.cull;
        frame.object_triangles = camera.object_triangles;
        frame.meshes = camera.meshes;  // a software depth buffer rasterises the light's view too
        if (options_.record_objects) {
            light_->decisions.clear();
            frame.decisions = &light_->decisions;
        }
        light_->device->resetCounters();
        light_->gl_device.beginDrawnSet(objects);
        light_->culler->cullAndRender(world_->tree(), frame, *light_->device);
        const DeviceCounters& c = light_->device->counters();
        stats.shadow_casters = static_cast<int64_t>(c.objects_drawn);
        stats.shadow_triangles = static_cast<int64_t>(c.triangles_drawn);
        stats.shadow_queries = static_cast<int64_t>(c.queries_issued);
    } else {
        cast_shadow_.assign(objects, 0);
        int64_t triangles = 0;
        for (const uint32_t o : shadow_casters_) {
            renderer_.drawObject(o);
            cast_shadow_[o] = 1;
            triangles += renderer_.triangleCount(o);
        }
        stats.shadow_casters = static_cast<int64_t>(shadow_casters_.size());
        stats.shadow_triangles = triangles;
        stats.shadow_queries = 0;
    }
    if (shadow_gpu_timer_) shadow_gpu_timer_->end();
    stats.shadow_cpu_ms = nowMs() - start;
}

// Stereo per eye, inside the frame's timing: the right eye culled by its own culler on its own
// device, into its half of the framebuffer, after the left eye's pass.
void Simulation::cullRightEye(const CullFrame& camera) {
    CullFrame frame = camera;
    frame.view = world_->stereoViews()->right;
    frame.decisions = nullptr;
    if (options_.record_objects) {
        right_eye_->decisions.clear();
        frame.decisions = &right_eye_->decisions;
    }
    if (algorithm_.oracle) frame.ground_truth_visible = right_truth_visible_;
    right_eye_->device->resetCounters();
    right_eye_->gl_device.beginDrawnSet(world_->scene().objectCount());
    renderer_.setEyes(StereoEyes::Right);
    right_eye_->culler->cullAndRender(world_->tree(), frame, *right_eye_->device);
    renderer_.setEyes(StereoEyes::Both);
}

void Simulation::splitEyeTruth(const GroundTruthFrame& truth) {
    const size_t objects = truth.eye_visible.size();
    left_truth_visible_.resize(objects);
    right_truth_visible_.resize(objects);
    for (size_t o = 0; o < objects; ++o) {
        left_truth_visible_[o] = truth.eye_visible[o] & 1u;
        right_truth_visible_[o] = (truth.eye_visible[o] >> 1) & 1u;
    }
}

// After the frame, outside the timing: the casters the light view's culler drew (a conditional
// draw counts when its query passed samples), for the missed casters.
void Simulation::resolveLightViewCasters() {
    const uint32_t objects = world_->scene().objectCount();
    light_->gl_device.resolveConditionalDraws();
    cast_shadow_.assign(objects, 0);
    for (uint32_t o = 0; o < objects; ++o) cast_shadow_[o] = light_->gl_device.drew(o) ? 1 : 0;
    light_->culler->afterFrame(*light_->device);
}

// Light-frustum culling: every object whose box overlaps the light's box; receiver-masked, of
// those only the ones that may shadow a point the camera's pass left in its depth buffer.
void Simulation::selectCasters(const ShadowView& shadow) {
    const std::vector<Aabb>& boxes = world_->state().boxes;
    const glm::dvec3& origin = world_->scene().culling_origin;
    objectsInLightBox(shadow.box, boxes, origin, shadow_casters_);
    if (!masksReceivers(options_.shadow_casters)) return;
    buildReceiverMask(shadow);
    std::erase_if(shadow_casters_,
                  [&](uint32_t o) { return !receiver_mask_.mayShadow(boxes[o], origin); });
}

// The receivers: every pixel the camera's pass covered, read back inside the frame (a wait for
// the camera's pass), grown by the shadow lookup's normal offset (1.5 texels) and one texel more.
void Simulation::buildReceiverMask(const ShadowView& shadow) {
    renderer_.readDepthRanks(camera_depth_);
    receiver_mask_.reset(shadow.box, kReceiverMaskResolution);
    const double margin = 2.5 * shadow_lookup_.texel_m;
    if (const StereoViews* stereo = world_->stereoViews()) {
        // Each eye's half of the framebuffer, through that eye's own view.
        for (int eye = 0; eye < 2; ++eye) {
            addVisibleReceivers(eyePixels(std::span<const uint32_t>(camera_depth_), eye),
                                renderer_.width(), renderer_.height() / 2,
                                eye == 0 ? stereo->left_render : stereo->right_render,
                                renderer_.depthConvention(), margin, receiver_mask_);
        }
        return;
    }
    addVisibleReceivers(camera_depth_, renderer_.width(), renderer_.height(), world_->view().render,
                        renderer_.depthConvention(), margin, receiver_mask_);
}

// Receiver-masked: the camera's pass drawn again with the shadow term over its own depth, each
// object it drew (GlRenderer::redrawObject), inside the frame's timing.
void Simulation::shadeCameraPass(FrameStats& stats) {
    const double start = nowMs();
    renderer_.setView(world_->view().render, world_->modelViews());
    renderer_.setShadow(&shadow_lookup_);
    renderer_.resumeFrame();
    if (shading_gpu_timer_) shading_gpu_timer_->begin();
    auto redraw = [&](const std::vector<uint8_t>& submitted) {
        for (size_t o = 0; o < submitted.size(); ++o) {
            if (submitted[o]) renderer_.redrawObject(static_cast<uint32_t>(o));
        }
    };
    if (right_eye_) {
        // Stereo per eye: each eye's half shaded with what that eye's pass drew.
        renderer_.setEyes(StereoEyes::Left);
        redraw(camera_submitted_);
        renderer_.setEyes(StereoEyes::Right);
        redraw(right_eye_submitted_);
        renderer_.setEyes(StereoEyes::Both);
    } else {
        redraw(camera_submitted_);
    }
    if (shading_gpu_timer_) shading_gpu_timer_->end();
    stats.shading_cpu_ms = nowMs() - start;
}

// The shadow term's error (sim/run/shadow_error.h), after the camera view's read-back.
void Simulation::measureShadowError(const GroundTruthFrame& truth, FrameStats& stats) {
    renderer_.readShadowTexels(culled_shadow_texels_);
    ShadowPixelCounts pixels =
        compareShadowTerms(truth.ids, truth.shadow_texels, culled_ids_, culled_shadow_texels_);
    if (pixels.error > 0) {
        // A difference: both maps read back (only now: a map is megabytes) to tell ties apart.
        truth_->readShadowDepth(truth_shadow_depth_);
        shadow_map_->readDepth(culled_shadow_depth_);
        pixels =
            compareShadowTerms(truth.ids, truth.shadow_texels, culled_ids_, culled_shadow_texels_,
                               truth_shadow_depth_, culled_shadow_depth_);
    }
    stats.shadow_error_pixels = pixels.error;
    stats.shadow_tie_pixels = pixels.tie;
    stats.missed_casters = countMissedCasters(truth.shadow_pixels, cast_shadow_);
    stats.shadow_seen_casters =
        std::count_if(truth.shadow_pixels.begin(), truth.shadow_pixels.end(),
                      [](uint32_t shadowed) { return shadowed > 0; });
}

void Simulation::recordAnswerLatencies(uint32_t frame, FrameStats& stats) {
    gl_device_.takeAnswerLatencies(frame_latencies_);
    if (right_eye_) {
        right_eye_->gl_device.takeAnswerLatencies(right_latencies_);
        frame_latencies_.insert(frame_latencies_.end(), right_latencies_.begin(),
                                right_latencies_.end());
    }
    stats.answers = frame_latencies_.size();
    segment_tallies_.addLatencies(frame, frame_latencies_);
    if (frame >= world_->scenario().warmup_frames) {
        for (uint32_t latency : frame_latencies_) {
            if (latency >= answer_latencies_.size())
                answer_latencies_.resize(size_t{latency} + 1, 0);
            ++answer_latencies_[latency];
        }
    }
    stats.answer_latency_median = medianLatency(frame_latencies_);
}

// Object IDs and depth compared pixel by pixel (sim/run/pixel_error.h: error or tie), and the
// objects ground truth saw against those the culler drew: a visible object is missed when it was
// not drawn. One it drew shows in ground truth's pixels at the same depth in both renders (the
// same fragments), so where another ID holds such a pixel it is a tie, not a miss.
void Simulation::measureError(const GroundTruthFrame& truth, FrameStats& stats) {
    const uint32_t objects = world_->scene().objectCount();
    renderer_.readObjectIds(culled_ids_);
    renderer_.readDepthRanks(culled_depth_);
    ++error_read_backs_;
    const PixelCounts pixels =
        comparePixels(truth.ids, truth.depth, culled_ids_, culled_depth_, truth.stray,
                      options_.record_objects ? &marks_ : nullptr);
    culled_visible_.assign(objects, 0);
    for (uint32_t id : culled_ids_) {
        if (id != 0) culled_visible_[id - 1] = 1;
    }
    // Conditional draws count as drawn when their query passed samples: one the device skipped
    // was not drawn; one it executed on a query that passed nothing cannot show.
    gl_device_.resolveConditionalDraws();
    if (right_eye_) right_eye_->gl_device.resolveConditionalDraws();
    int64_t missed = 0, tied_away = 0, visible = 0, overdrawn = 0, overdrawn_triangles = 0;
    missing_.assign(objects, 0);
    verdicts_.resize(objects);
    const Scene& scene = world_->scene();
    for (uint32_t o = 0; o < objects; ++o) {
        // Stereo per eye: drawn by either eye's pass; missed when an eye that sees it did not
        // draw it.
        const bool left_drew = gl_device_.drew(o);
        const bool right_drew = right_eye_ && right_eye_->gl_device.drew(o);
        const bool drawn = left_drew || right_drew;
        const bool eye_missed = right_eye_ && ((truth.eye_visible[o] & 1u && !left_drew) ||
                                               (truth.eye_visible[o] & 2u && !right_drew));
        verdicts_[o] = static_cast<uint8_t>(
            truth.visible[o] ? (drawn ? ObjectVerdict::DrawnVisible : ObjectVerdict::Missed)
                             : (drawn ? ObjectVerdict::DrawnHidden : ObjectVerdict::Culled));
        if (!truth.visible[o]) {
            // Drawn, and not a pixel of it in the full render: over-draw.
            overdrawn += drawn;
            if (drawn) overdrawn_triangles += scene.meshes[scene.object_mesh[o]].triangleCount();
            continue;
        }
        ++visible;
        missing_[o] = !drawn || eye_missed;
        missed += missing_[o];
        tied_away += drawn && !culled_visible_[o];
    }
    popping_.addFrame(missing_);
    segment_tallies_.addMissing(stats.frame, missing_);
    if (options_.record_objects) recordObjects(truth);
    light_object_frames_.clear();
    if (truth.has_shadow) {
        measureShadowError(truth, stats);
        if (options_.record_objects && light_ && stats.shadow_casters >= 0) {
            recordLightObjects(truth);
        }
    }
    if (world_->stereoViews() != nullptr) {
        // Each eye's error apart: the left eye's half of the framebuffer compared again, the
        // right eye's the rest of the frame's.
        auto left = [&](const auto& v) { return eyePixels(std::span(v), 0); };
        stats.left_error_pixels =
            comparePixels(left(truth.ids), left(truth.depth), left(culled_ids_),
                          left(culled_depth_), left(truth.stray), nullptr)
                .error;
        stats.right_error_pixels = pixels.error - stats.left_error_pixels;
    }
    stats.error_pixels = pixels.error;
    stats.tie_pixels = pixels.tie;
    stats.stray_pixels = pixels.stray;
    stats.missed_objects = missed;
    stats.tied_away_objects = tied_away;
    stats.visible_objects = visible;
    stats.overdrawn_objects = overdrawn;
    stats.overdrawn_triangles = overdrawn_triangles;
    if (options_.keep_worst_error_frame && pixels.error > worst_.error_pixels) {
        worst_.frame = stats.frame;
        worst_.error_pixels = pixels.error;
        worst_.tie_pixels = pixels.tie;
        worst_.culled_ids = culled_ids_;
        worst_.truth_ids = truth.ids;
        worst_.truth_rgba = truth.rgba;
        comparePixels(truth.ids, truth.depth, culled_ids_, culled_depth_, truth.stray,
                      &worst_.differences);
        renderer_.readColor(worst_.culled_rgba);
    }
}

// Each object's decision, reason and pixels, after the frame: the log resolved on the tree as the
// culler left it (no configuration changes it), the drawn set as the device resolved it.
void Simulation::recordObjects(const GroundTruthFrame& truth) {
    const uint32_t objects = world_->scene().objectCount();
    const BspTree& tree = world_->tree();
    resolveDecisions(tree, decisions_.records(), reasons_, resolve_stack_, &reason_subjects_);
    if (!right_eye_) {
        attributePixels(truth.ids, truth.stray, culled_ids_, marks_, objects, object_pixels_);
    } else {
        // Per eye, each eye's decisions go with its own half's pixels.
        auto half = [&](const auto& v, int eye) { return eyePixels(std::span(v), eye); };
        attributePixels(half(truth.ids, 0), half(truth.stray, 0), half(culled_ids_, 0),
                        half(marks_, 0), objects, object_pixels_);
        attributePixels(half(truth.ids, 1), half(truth.stray, 1), half(culled_ids_, 1),
                        half(marks_, 1), objects, right_eye_pixels_);
        resolveDecisions(tree, right_eye_->decisions.records(), right_eye_reasons_, resolve_stack_,
                         &right_eye_subjects_);
    }
    fillObjectFrames(tree, reasons_, reason_subjects_, gl_device_, object_pixels_, objects,
                     object_frames_);
    if (right_eye_) {
        fillObjectFrames(tree, right_eye_reasons_, right_eye_subjects_, right_eye_->gl_device,
                         right_eye_pixels_, objects, right_eye_object_frames_);
    } else {
        right_eye_object_frames_.clear();
    }
}

// The light view's decisions, as recordObjects() the camera's: each caster's reason from the light
// culler's log, whether it was drawn into the map, and the visible pixels ground truth shadows
// through it (GroundTruthFrame::shadow_pixels).
void Simulation::recordLightObjects(const GroundTruthFrame& truth) {
    const uint32_t objects = world_->scene().objectCount();
    const BspTree& tree = world_->tree();
    resolveDecisions(tree, light_->decisions.records(), light_reasons_, resolve_stack_,
                     &light_subjects_);
    light_object_frames_.resize(objects);
    for (uint32_t o = 0; o < objects; ++o) {
        ObjectFrame& f = light_object_frames_[o];
        f.why = o < light_reasons_.size() ? light_reasons_[o] : Decision{};
        f.drawn = cast_shadow_[o] != 0;
        f.pixels = ObjectPixels{};
        f.pixels.truth = truth.shadow_pixels[o];
        f.pixels.error = f.drawn ? 0 : truth.shadow_pixels[o];
        setDecidingNode(tree, o < light_subjects_.size() ? light_subjects_[o] : QueryTag{}, f);
    }
}

}  // namespace occsim
