#include "sim/run/simulation.h"

#include "culling/basic_cullers.h"
#include "sim/world/camera_path.h"

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

DepthConvention depthConventionOf(const Scenario& scenario) {
    return scenario.conventional_depth ? DepthConvention::Conventional24
                                       : DepthConvention::ReverseFloat;
}

FrameView makeFrameView(const CameraSpec& camera, double time_s, uint32_t width, uint32_t height,
                        const glm::dvec3& culling_origin, DepthConvention depth) {
    return makeFrameView(camera, sampleCameraPath(camera, time_s), width, height, culling_origin,
                         depth);
}

FrameView makeFrameView(const CameraSpec& camera, const CameraPose& pose, uint32_t width,
                        uint32_t height, const glm::dvec3& culling_origin, DepthConvention depth) {
    const glm::dvec3 forward = glm::normalize(pose.target - pose.position);
    // Looking straight up or down: y cannot be the up vector, take z.
    const glm::dvec3 up = std::abs(forward.y) > 0.999 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0);
    const double aspect = static_cast<double>(width) / height;
    const double fov = glm::radians(camera.fov_y_deg);

    FrameView view;
    view.render.eye = pose.position;
    view.render.box_origin = culling_origin;
    view.render.view_rotation = glm::mat4(glm::lookAt(glm::dvec3(0.0), forward, up));
    view.render.projection = perspectiveFor(depth, static_cast<float>(fov),
                                            static_cast<float>(aspect),
                                            static_cast<float>(camera.near_m),
                                            static_cast<float>(camera.far_m));
    // Culling uses the conventional OpenGL projection, in the culling frame: the eye relative to
    // the culling origin is computed in double, so the planes are as precise as the boxes.
    const glm::dvec3 eye = pose.position - culling_origin;
    const glm::dmat4 view_projection = glm::perspective(fov, aspect, camera.near_m, camera.far_m) *
                                       glm::lookAt(eye, eye + forward, up);
    view.cull.eye = glm::vec3(eye);
    view.cull.frustum = frustumFromViewProjection(glm::mat4(view_projection));
    view.cull.near_radius = static_cast<float>(nearPlaneCornerDistance(camera.near_m, fov, aspect));
    return view;
}

void uploadScene(const Scene& scene, GlRenderer& renderer) {
    renderer.uploadMeshes(scene.meshes);
    renderer.setObjectMeshes(scene.object_mesh);
}

Simulation::Simulation(const Scene& scene, const Scenario& scenario,
                       const AlgorithmTraits& algorithm, std::unique_ptr<Culler> culler,
                       const CullerOptions& options, GlRenderer& renderer,
                       const SimulationOptions& sim_options)
    : scene_(scene),
      scenario_(scenario),
      algorithm_(algorithm),
      culler_(std::move(culler)),
      renderer_(renderer),
      options_(sim_options),
      gl_device_(renderer, sim_options.latency),
      ground_truth_device_(renderer, LatencyMode{}),
      approximate_device_(algorithm.issues_queries && options.approximation.active()
                              ? std::make_unique<ApproximateDevice>(gl_device_, options.approximation)
                              : nullptr),
      device_(approximate_device_ ? static_cast<RenderDevice*>(approximate_device_.get())
                                  : &gl_device_),
      tracer_(*device_),
      state_(initialState(scene)) {
    requireFiniteBoxes(state_, 0);
    tree_.build(state_.boxes, scenario.bsp);
    culler_->reset(tree_);
    model_view_.resize(scene.objectCount());
    object_triangles_.resize(scene.objectCount());
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        object_triangles_[o] = scene.meshes[scene.object_mesh[o]].triangleCount();
    }
}

void Simulation::computeModelViews() {
    // Camera-relative model-view matrices, composed in double: precise far from the origin.
    // Once per frame: ground truth and the culled render of this frame both use them.
    const glm::dmat4 rotation(view_.render.view_rotation);
    const glm::dmat4 to_eye = glm::translate(glm::dmat4(1.0), -view_.render.eye);
    for (uint32_t o = 0; o < scene_.objectCount(); ++o) {
        model_view_[o] = glm::mat4(rotation * to_eye * modelMatrix(state_.poses[o]));
    }
}

bool Simulation::needsGroundTruth() const {
    return options_.measure_error || algorithm_.oracle;
}

void Simulation::advance() {
    FrameStats& stats = pending_;
    stats = FrameStats{};
    stats.frame = frame_;
    const double since_start_s = frame_ * scenario_.dt_s;
    stats.time_s = scenario_.start_time_s + since_start_s;

    // The world moves (not on frame 0: it shows the initial state). Skipped without movers.
    const auto update_start = Clock::now();
    if (frame_ > 0 && !state_.movers.empty() && !live_.hold_world) {
        const uint64_t moved_before = tree_.stats().reinserts_moved;
        stepMovers(scene_, state_, scenario_.dt_s);
        requireFiniteBoxes(state_, frame_);
        for (const Mover& mover : state_.movers) tree_.reinsert(mover.object, state_.boxes[mover.object]);
        tree_.refitDirtyBounds();
        stats.moved_objects = state_.movers.size();
        stats.node_changes = tree_.stats().reinserts_moved - moved_before;
    }
    stats.update_ms = msSince(update_start);

    const uint32_t width = live_.width > 0 ? live_.width : scenario_.width;
    const uint32_t height = live_.height > 0 ? live_.height : scenario_.height;
    const DepthConvention depth = depthConventionOf(scenario_);
    view_ = live_.camera ? makeFrameView(scenario_.camera, *live_.camera, width, height,
                                         scene_.culling_origin, depth)
                         : makeFrameView(scenario_.camera, since_start_s, width, height,
                                         scene_.culling_origin, depth);
    computeModelViews();
    cull_frame_ = CullFrame{};
    cull_frame_.frame_index = frame_;
    cull_frame_.time_s = stats.time_s;
    cull_frame_.view = view_.cull;
    cull_frame_.object_triangles = object_triangles_;
    advanced_ = true;
}

const GroundTruthFrame& Simulation::renderGroundTruth(bool with_colour) {
    // Every object, in index order, with no culling code on the way: the GPU clips. A culler's
    // mistake (a frustum test rounding the wrong way) cannot hide itself in its own ground truth.
    renderer_.setView(view_.render, model_view_);
    renderer_.beginFrame();
    for (uint32_t o = 0; o < scene_.objectCount(); ++o) ground_truth_device_.drawObject(o);
    renderer_.readObjectIds(ground_truth_.ids);
    if (with_colour) renderer_.readColor(ground_truth_.rgba);
    ground_truth_.visible.assign(scene_.objectCount(), 0);
    for (uint32_t id : ground_truth_.ids) {
        if (id != 0) ground_truth_.visible[id - 1] = 1;
    }
    return ground_truth_;
}

FrameStats Simulation::renderFrame(const GroundTruthFrame* shared) {
    if (!advanced_) advance();
    FrameStats stats = pending_;

    // Ground truth, outside the timing, when error is measured or the culler is the oracle.
    const GroundTruthFrame* truth = nullptr;
    if (needsGroundTruth()) {
        truth = shared ? shared : &renderGroundTruth(options_.keep_worst_error_frame);
        cull_frame_.ground_truth_visible = truth->visible;
    }

    // The measured frame: culled render to glFinish.
    renderer_.setView(view_.render, model_view_);
    device_->resetCounters();
    const auto frame_start = Clock::now();
    renderer_.beginFrame();
    const auto cull_start = Clock::now();
    const bool trace =
        live_.trace_every_frame || (options_.trace_frame && *options_.trace_frame == frame_);
    if (trace) tracer_.beginTrace(frame_);
    culler_->cullAndRender(tree_, cull_frame_, trace ? tracer_ : *device_);
    tracer_.endTrace();
    traced_ |= trace;
    const double cull_ms = msSince(cull_start);
    renderer_.finish();
    stats.frame_ms = msSince(frame_start);

    const DeviceCounters& c = device_->counters();
    stats.wait_ms = c.wait_seconds * 1e3;
    stats.cull_cpu_ms = std::max(0.0, cull_ms - (c.submit_seconds + c.wait_seconds) * 1e3);
    stats.queries = c.queries_issued;
    stats.objects_drawn = c.objects_drawn;
    stats.triangles = c.triangles_drawn;

    if (options_.measure_error) measureError(*truth, stats);
    ++frame_;
    advanced_ = false;
    return stats;
}

void Simulation::continueFrom(const Simulation& other) {
    // Between frames only: a half-done frame (advanced, not rendered) would be lost.
    if (other.advanced_ || advanced_) {
        throw std::logic_error("Simulation::continueFrom between advance() and renderFrame()");
    }
    state_ = other.state_;
    tree_ = other.tree_;
    frame_ = other.frame_;
    culler_->reset(tree_);
}

// Object-ID buffers compared pixel by pixel; an object counts as missed when ground truth saw it
// and the culled frame shows none of its pixels (a culled frame draws a subset of the objects, so
// an object it drew that ground truth sees cannot be hidden in it).
void Simulation::measureError(const GroundTruthFrame& truth, FrameStats& stats) {
    renderer_.readObjectIds(culled_ids_);
    int64_t differing = 0;
    culled_visible_.assign(scene_.objectCount(), 0);
    for (size_t i = 0; i < culled_ids_.size(); ++i) {
        differing += culled_ids_[i] != truth.ids[i];
        if (culled_ids_[i] != 0) culled_visible_[culled_ids_[i] - 1] = 1;
    }
    int64_t missed = 0, visible = 0;
    missing_.assign(scene_.objectCount(), 0);
    for (uint32_t o = 0; o < scene_.objectCount(); ++o) {
        visible += truth.visible[o];
        missing_[o] = truth.visible[o] && !culled_visible_[o];
        missed += missing_[o];
    }
    popping_.addFrame(missing_);
    stats.error_pixels = differing;
    stats.missed_objects = missed;
    stats.visible_objects = visible;
    if (options_.keep_worst_error_frame && differing > worst_.error_pixels) {
        worst_.frame = stats.frame;
        worst_.error_pixels = differing;
        worst_.culled_ids = culled_ids_;
        worst_.truth_ids = truth.ids;
        worst_.truth_rgba = truth.rgba;
        renderer_.readColor(worst_.culled_rgba);
    }
}

}  // namespace occsim
