#include "sim/run/shared_world.h"

#include <atomic>
#include <chrono>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <string>

#include "sim/scene/occluder_mesh.h"

namespace occsim {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Frame serials are handed out process-wide (see SharedWorld::frameSerial()); atomic because
// tests may run worlds on several threads.
std::atomic<uint64_t> g_next_serial{1};

std::string objectName(const Scene& scene, uint32_t object) {
    return object < scene.object_names.size() && !scene.object_names[object].empty()
               ? scene.object_names[object]
               : "object " + std::to_string(object);
}

// "mesh 3 (of 'Crate' and 11 other objects) has no inscribed occluder mesh: <why>; they occlude
// with their own mesh in masked"; `first` and `users`: the objects that would occlude with it.
std::string occluderRefusalLine(const Scene& scene, uint32_t mesh, uint32_t first, uint32_t users,
                                const std::string& why) {
    std::string line = "mesh " + std::to_string(mesh) + " (of '" + objectName(scene, first) + "'";
    if (users > 1) line += " and " + std::to_string(users - 1) + " other objects";
    return line + ") has no inscribed occluder mesh: " + why + "; " +
           (users > 1 ? "they occlude with their" : "it occludes with its") + " own mesh in masked";
}

// "the occluder mesh of 'Wall' (mesh 5): <what>"
std::string authoredRefusalLine(const Scene& scene, uint32_t object, uint32_t mesh,
                                const std::string& what) {
    return "the occluder mesh of '" + objectName(scene, object) + "' (mesh " +
           std::to_string(mesh) + "): " + what;
}

}  // namespace

// The mesh appended to the flat arrays after what they hold; its range's index.
uint32_t SharedWorld::appendCullMesh(FlatMeshes& f, const MeshData& mesh) {
    MeshRange range;
    range.first_index = static_cast<uint32_t>(f.indices.size());
    range.index_count = static_cast<uint32_t>(mesh.indices.size());
    range.first_vertex = static_cast<uint32_t>(f.positions.size());
    range.vertex_count = static_cast<uint32_t>(mesh.positions.size());
    f.positions.insert(f.positions.end(), mesh.positions.begin(), mesh.positions.end());
    f.indices.insert(f.indices.end(), mesh.indices.begin(), mesh.indices.end());
    f.meshes.push_back(range);
    return static_cast<uint32_t>(f.meshes.size() - 1);
}

SharedWorld::SharedWorld(const Scene& scene, const Scenario& scenario)
    : scene_(scene), scenario_(scenario), state_(initialState(scene)) {
    requireFiniteBoxes(state_, 0);
    tree_.build(state_.boxes, scenario.bsp);
    model_view_.resize(scene.objectCount());
    object_triangles_.resize(scene.objectCount());
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        object_triangles_[o] = scene.meshes[scene.object_mesh[o]].triangleCount();
    }
    if (const int light = firstShadowLight(scene.lights); light >= 0) {
        shadow_.emplace();
        shadow_->light = static_cast<uint32_t>(light);
        shadow_->map_size = scene.lights[light].shadow_map;
        shadow_->model_views.resize(scene.objectCount());
    }
}

void SharedWorld::computeShadowView(const CameraPose& pose, double aspect, DepthConvention depth) {
    ShadowView& shadow = *shadow_;
    const CameraSpec& camera = scenario_.camera;
    auto corners = viewFrustumCorners(pose.position, pose.target, camera.fov_y_deg, aspect,
                                      camera.near_m, camera.far_m);
    if (scenario_.stereo) {
        // Both eyes' frusta (docs/views.md): the left eye's left corners and the right eye's
        // right ones hold both, the eyes being shifted along the camera's right.
        const glm::dvec3 half =
            0.5 * scenario_.stereo->eye_separation_m * glm::normalize(corners[1] - corners[0]);
        const auto left = viewFrustumCorners(pose.position - half, pose.target - half,
                                             camera.fov_y_deg, aspect, camera.near_m, camera.far_m);
        const auto right =
            viewFrustumCorners(pose.position + half, pose.target + half, camera.fov_y_deg, aspect,
                               camera.near_m, camera.far_m);
        for (const int i : {0, 3, 4, 7}) corners[i] = left[i];
        for (const int i : {1, 2, 5, 6}) corners[i] = right[i];
    }
    // The scene's bounds this frame: the tree's root bounds over every object's box, moved ones
    // included (refit in advance()), in the world.
    const Aabb& root = tree_.bounds(0);
    WorldBox scene_box;
    if (root.min.x <= root.max.x) {
        scene_box.min = glm::dvec3(root.min) + scene_.culling_origin;
        scene_box.max = glm::dvec3(root.max) + scene_.culling_origin;
    }
    shadow.box = fitDirectionalLight(scene_.lights[shadow.light].direction, corners, scene_box);
    if (shadow.box.empty) return;
    shadow.render = makeLightRenderView(shadow.box, scene_.culling_origin, depth);
    shadow.cull = makeLightCullView(shadow.box, scene_.culling_origin, shadow.map_size);
    const glm::dmat4 rotation(shadow.render.view_rotation);
    const glm::dmat4 to_eye = glm::translate(glm::dmat4(1.0), -shadow.render.eye);
    for (uint32_t o = 0; o < scene_.objectCount(); ++o) {
        shadow.model_views[o] = glm::mat4(rotation * to_eye * modelMatrix(state_.poses[o]));
    }
}

void SharedWorld::computeModelViews() {
    // Camera-relative model-view matrices, composed in double: precise far from the origin.
    // Once per frame: ground truth and every configuration's culled render use them.
    const glm::dmat4 rotation(view_.render.view_rotation);
    const glm::dmat4 to_eye = glm::translate(glm::dmat4(1.0), -view_.render.eye);
    for (uint32_t o = 0; o < scene_.objectCount(); ++o) {
        model_view_[o] = glm::mat4(rotation * to_eye * modelMatrix(state_.poses[o]));
    }
}

const CullMeshes& SharedWorld::cullMeshes() {
    if (!flat_meshes_) {
        flat_meshes_ = std::make_unique<FlatMeshes>();
        FlatMeshes& f = *flat_meshes_;
        for (const MeshData& mesh : scene_.meshes) appendCullMesh(f, mesh);
        // Inscribed occluder meshes, once per mesh some object may occlude with, after the
        // scene's meshes; and every object's role.
        const auto start = Clock::now();
        const auto scene_meshes = static_cast<uint32_t>(scene_.meshes.size());
        std::vector<uint32_t> occluder_of(scene_meshes, kNoOccluderMesh);
        // Per mesh, the objects that may occlude with a made occluder of it (those with an
        // authored one are checked below instead): how many, and the first.
        std::vector<uint32_t> users(scene_meshes, 0), first_user(scene_meshes, 0);
        f.object_occluder.assign(scene_.objectCount(), kOccluderBySize);
        for (uint32_t o = 0; o < scene_.objectCount(); ++o) {
            const OccluderRole role = o < scene_.object_occluder.size() ? scene_.object_occluder[o]
                                                                        : OccluderRole::BySize;
            f.object_occluder[o] = role == OccluderRole::Always  ? kOccluderAlways
                                   : role == OccluderRole::Never ? kOccluderNever
                                                                 : kOccluderBySize;
            const bool authored_mesh = o < scene_.object_occluder_mesh.size() &&
                                       scene_.object_occluder_mesh[o] < scene_meshes;
            if (role == OccluderRole::Never || authored_mesh) continue;
            const uint32_t m = scene_.object_mesh[o];
            if (users[m]++ == 0) first_user[m] = o;
        }
        for (uint32_t m = 0; m < scene_meshes; ++m) {
            // A mesh too small to gain (a box) is its own occluder: neither tried nor noted.
            if (users[m] == 0 ||
                scene_.meshes[m].triangleCount() < OccluderMeshSettings{}.min_triangles)
                continue;
            ++occluder_cost_.tried;
            const OccluderMesh made = makeInscribedOccluder(scene_.meshes[m]);
            if (made.mesh.indices.empty()) {
                occluder_cost_.refusals.push_back(
                    occluderRefusalLine(scene_, m, first_user[m], users[m], made.refusal));
                continue;
            }
            ++occluder_cost_.made;
            occluder_of[m] = appendCullMesh(f, made.mesh);
        }
        f.object_occluder_mesh.resize(scene_.objectCount());
        for (uint32_t o = 0; o < scene_.objectCount(); ++o) {
            f.object_occluder_mesh[o] = occluder_of[scene_.object_mesh[o]];
        }
        // Occluder meshes someone made (glTF extras.occsim_occluder_mesh), checked against their
        // object's solid once per pair of meshes; they stand in for a made one.
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> authored;  // (object's, its) -> range
        for (uint32_t o = 0; o < scene_.objectCount(); ++o) {
            const uint32_t a = o < scene_.object_occluder_mesh.size()
                                   ? scene_.object_occluder_mesh[o]
                                   : kNoAuthoredOccluder;
            if (a >= scene_meshes || f.object_occluder[o] == kOccluderNever) continue;
            const std::pair<uint32_t, uint32_t> key{scene_.object_mesh[o], a};
            auto it = authored.find(key);
            if (it == authored.end()) {
                ++occluder_cost_.tried;
                const OccluderMesh checked =
                    checkAuthoredOccluder(scene_.meshes[key.first], scene_.meshes[a]);
                uint32_t range = kNoOccluderMesh;
                if (checked.mesh.indices.empty()) {
                    occluder_cost_.refusals.push_back(authoredRefusalLine(scene_, o, a,
                                                                          checked.refusal +
                                                                              "; it occludes with "
                                                                              "its own mesh"));
                } else {
                    ++occluder_cost_.made;
                    range = appendCullMesh(f, checked.mesh);
                    if (checked.dropped_triangles > 0) {
                        const uint32_t all = scene_.meshes[a].triangleCount();
                        occluder_cost_.refusals.push_back(authoredRefusalLine(
                            scene_, o, a,
                            std::to_string(checked.dropped_triangles) + " of its " +
                                std::to_string(all) +
                                " triangles do not lie inside its object and are left out"));
                    }
                }
                it = authored.emplace(key, range).first;
            }
            if (it->second != kNoOccluderMesh) f.object_occluder_mesh[o] = it->second;
        }
        occluder_cost_.ms = msSince(start);
        f.object_to_culling.resize(scene_.objectCount());
        f.view.object_occluder = f.object_occluder;
        f.view.object_occluder_mesh = f.object_occluder_mesh;
        f.view.positions = f.positions;
        f.view.indices = f.indices;
        f.view.meshes = f.meshes;
        f.view.object_mesh = scene_.object_mesh;
        f.view.object_to_culling = f.object_to_culling;
    }
    FlatMeshes& f = *flat_meshes_;
    if (f.transforms_serial != serial_) {
        // Relative to the culling origin in double, then float: precise however far the scene
        // lies from the world origin (the boxes are in the same frame).
        const glm::dmat4 to_culling = glm::translate(glm::dmat4(1.0), -scene_.culling_origin);
        for (uint32_t o = 0; o < scene_.objectCount(); ++o) {
            f.object_to_culling[o] = glm::mat4(to_culling * modelMatrix(state_.poses[o]));
        }
        f.transforms_serial = serial_;
    }
    return f.view;
}

void SharedWorld::advance() {
    frame_ = advances_++;
    serial_ = g_next_serial.fetch_add(1, std::memory_order_relaxed);
    FrameStats& stats = stats_;
    stats = FrameStats{};
    stats.frame = frame_;
    const double since_start_s = frame_ * scenario_.dt_s;
    stats.time_s = scenario_.start_time_s + since_start_s;

    // The world moves (not on frame 0: it shows the initial state). Skipped without movers.
    const auto update_start = Clock::now();
    if (frame_ > 0 && !state_.moved.empty() && !live_.hold_world) {
        const uint64_t moved_before = tree_.stats().reinserts_moved;
        stepMovers(scene_, state_, scenario_.dt_s);
        requireFiniteBoxes(state_, frame_);
        for (const uint32_t o : state_.moved) tree_.reinsert(o, state_.boxes[o]);
        tree_.refitDirtyBounds();
        stats.moved_objects = state_.moved.size();
        stats.node_changes = tree_.stats().reinserts_moved - moved_before;
        ++steps_;
    }
    stats.update_ms = msSince(update_start);
    update_ms_total_ += stats.update_ms;

    const uint32_t width = live_.width > 0 ? live_.width : scenario_.width;
    const uint32_t height = live_.height > 0 ? live_.height : scenario_.height;
    const DepthConvention depth = depthConventionOf(scenario_);
    const CameraPose pose =
        live_.camera ? *live_.camera : sampleCameraPath(scenario_.camera, since_start_s);
    if (scenario_.stereo) {
        stereo_ = makeStereoViews(scenario_.camera, pose, scenario_.stereo->eye_separation_m, width,
                                  height, scene_.culling_origin, depth);
        view_.render = stereo_->render;
        view_.cull = cullsEachEye() ? stereo_->left : stereo_->enclosing;
    } else {
        view_ = makeFrameView(scenario_.camera, pose, width, height, scene_.culling_origin, depth);
    }
    computeModelViews();
    if (shadow_) computeShadowView(pose, static_cast<double>(width) / height, depth);
    cull_frame_ = CullFrame{};
    cull_frame_.frame_index = frame_;
    cull_frame_.time_s = stats.time_s;
    cull_frame_.view = view_.cull;
    cull_frame_.object_triangles = object_triangles_;
}

}  // namespace occsim
