// The simulated world: immutable scene content (meshes, which mesh each object draws, the initial
// poses, the movers' starting state, the paths movers follow) built once from a scenario, and the
// per-run mutable state (poses, world boxes, movers), which a run keeps once and every
// configuration renders (sim/run/shared_world.h).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "occsim/culling/geometry/aabb.h"
#include "occsim/culling/geometry/random.h"
#include "render/mesh_data.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scene_specs.h"
#include "sim/scene/model_animation.h"

namespace occsim {

// model = translate(position) * rotate(rotation) * linear. Position in double: scenes may sit far
// from the origin, and rendering is camera-relative. `linear` holds the model's own scale and
// orientation (a teapot's size, a glTF node's matrix); movers change position and rotation.
struct ObjectPose {
    glm::dvec3 position{0.0};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::mat3 linear{1.0f};
};

// Straight line at constant velocity, reflected at the region's faces (object position).
struct BounceMotion {
    glm::dvec3 velocity{0.0};
    WorldBox region;
};

// Circle around a vertical axis through `center`, at constant speed.
struct OrbitMotion {
    glm::dvec3 center{0.0};
    double radius_m = 1.0;
    double angular_speed = 0.0;  // radians per second (signed)
    double angle = 0.0;
};

// Along a closed path (Scene::paths) at constant speed, facing the direction of travel.
struct PathMotion {
    uint32_t path = 0;
    double distance_m = 0.0;  // along the path from its first point
    double speed_mps = 0.0;
};

// Horizontal wandering: constant speed, heading changing by a random amount each step, reflected
// at the region's faces. Seeded per mover, so it is deterministic for a given dt.
struct RandomWalkMotion {
    double speed_mps = 0.0;
    double heading = 0.0;    // radians about y; 0 = +x
    double turn_rate = 0.0;  // radians per second, largest change
    WorldBox region;
    Rng rng{0};
};

// Turning in place about the vertical axis.
struct SpinMotion {
    double angular_speed = 0.0;  // radians per second
    double angle = 0.0;
    glm::quat base{1.0f, 0.0f, 0.0f, 0.0f};
};

using Motion = std::variant<BounceMotion, OrbitMotion, PathMotion, RandomWalkMotion, SpinMotion>;

// A mover moves one object, or (copy >= 0) a whole copy of a glTF model: then its motion moves
// the copy's anchor (WorldState::copies) and `object` is the copy's first object.
struct Mover {
    uint32_t object = 0;
    Motion motion;
    int32_t copy = -1;
};

// A glTF source's model as the scene plays it: which of its animations play and how, and which
// objects of a copy they move.
inline constexpr uint32_t kNoAuthoredOccluder = 0xffffffffu;

struct SceneModel {
    std::shared_ptr<const AnimatedModel> model;
    uint32_t source = 0;                    // index into Scenario::sources
    std::vector<uint8_t> playing;           // per animation of the model
    std::vector<uint8_t> object_animated;   // per object of a copy: moved by a playing animation
    std::vector<uint32_t> object_mesh;      // per object of a copy: its mesh in Scene::meshes
    std::vector<std::string> object_names;  // per object of a copy: its node's name
    std::vector<OccluderRole> object_occluder;  // per object of a copy
    std::vector<uint32_t>
        object_occluder_mesh;  // per object of a copy (Scene's), or kNoAuthoredOccluder
    double speed = 1.0;
    AnimationMode mode = AnimationMode::Loop;
    double time_offset_s = 0.0;

    uint32_t objectsPerCopy() const { return static_cast<uint32_t>(object_animated.size()); }
};

// A copy of a glTF model that moves: its animations pose its objects, a whole-copy mover moves
// its anchor, or both. Each object's model matrix is
// T(anchor.position) · R(anchor.rotation) · anchor.linear · (the model's posed world matrix).
struct ModelCopy {
    uint32_t model = 0;         // index into Scene::models
    uint32_t first_object = 0;  // its objects: first_object .. first_object + objects per copy - 1
    ObjectPose anchor;          // position: the copy's origin; linear: its yaw (and spawn scale)
    double phase_s = 0.0;       // added to its animations' time
    bool animated = false;      // a playing animation moves some of its objects
    bool rigid = false;         // a mover moves the whole copy
};

// Per world: the buffers posing models needs, sized once (so a step allocates nothing).
struct ModelPoseBuffers {
    std::vector<ModelPoseScratch> per_model;
    std::vector<std::vector<double>> animation_times;  // per model, per animation
};

// A closed polyline with its cumulative arc lengths (lengths[i] = distance from point 0 to i;
// the last entry closes the loop back to point 0).
struct MotionPath {
    std::vector<glm::dvec3> points;
    std::vector<double> lengths;  // points.size() + 1 entries
    double total() const { return lengths.back(); }
};

struct Scene {
    std::vector<MeshData> meshes;
    std::vector<Aabb> mesh_bounds;      // model space, per mesh
    std::vector<uint32_t> object_mesh;  // per object
    // Per object, what a person calls it (objects.sqlite, `occsim why`): the glTF node's name
    // ("statue.042", "#k" added for copy k of a replicated model), or its source's kind and its
    // place in the source ("teapot 17"), or the mover that spawned it.
    std::vector<std::string> object_names;
    // Per object, whether a software depth buffer may use it as an occluder (OccluderRole).
    std::vector<OccluderRole> object_occluder;
    // Per object, the occluder mesh someone made for it (a glTF node's
    // extras.occsim_occluder_mesh): a mesh of `meshes` in the object's space, or
    // kNoAuthoredOccluder; checked against the object's solid before use (SharedWorld).
    std::vector<uint32_t> object_occluder_mesh;
    std::vector<ObjectPose> initial_poses;
    std::vector<Mover> initial_movers;
    std::vector<MotionPath> paths;
    std::vector<SceneModel> models;         // one per glTF source (and per spawned model's source)
    std::vector<ModelCopy> initial_copies;  // the copies that move
    std::vector<std::string> warnings;      // from sources (e.g. glTF parts skipped)
    // The lights: the scenario's ("lights"), then each placed glTF source's (KHR_lights_punctual)
    // in world space (docs/views.md).
    std::vector<LightSpec> lights;
    uint64_t triangle_count = 0;  // over all objects
    // The origin of the culling frame, in world coordinates (metres, double): the centre of the
    // camera path's keyframe positions, rounded to whole metres. Object boxes, the BSP tree, the
    // frustum and the eye given to cullers are all relative to it, so float keeps its precision
    // where the camera is, however far from the world origin the scene lies or its objects go,
    // and a scene moved by whole metres culls exactly alike.
    glm::dvec3 culling_origin{0.0};

    uint32_t objectCount() const { return static_cast<uint32_t>(object_mesh.size()); }
};

struct WorldState {
    std::vector<ObjectPose> poses;
    std::vector<Aabb> boxes;  // per object, relative to Scene::culling_origin (float, rounded out)
    std::vector<Mover> movers;
    std::vector<ModelCopy> copies;
    // Every object a step may move (the movers' own objects, the objects of rigid copies, the
    // animated objects of animated copies), each once: what a frame reinserts into the tree and
    // counts in moved_objects.
    std::vector<uint32_t> moved;
    double time_s = 0.0;  // simulation time since frame 0: what animations play at
    ModelPoseBuffers pose_buffers;
};

// Builds the scene a scenario describes; deterministic for a given scenario (and its seed).
// Throws ScenarioError for movers that do not fit their source (an object index past its end, a
// path motion on a source without lanes) and GltfError for unusable glTF files.
Scene buildScene(const Scenario& scenario);

WorldState initialState(const Scene& scene);

glm::dmat4 modelMatrix(const ObjectPose& pose);
// The box of a mesh under a pose, relative to `origin`: computed in double, then rounded outward
// to float, so that it always contains the object however far from the origin it is.
Aabb worldBox(const Aabb& mesh_bounds, const ObjectPose& pose, const glm::dvec3& origin = {});

// Advances every mover by dt seconds, poses the moving copies of glTF models at the new time, and
// refreshes the world boxes of every object in `moved`.
void stepMovers(const Scene& scene, WorldState& state, double dt_s);

// A motion (or a placement) that took an object out of finite float coordinates: the run cannot
// go on, since no culling decision about such an object means anything. The message names the
// object and the frame.
class MotionError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Throws MotionError for the first object whose world box is not finite: every object on frame
// 0 (placements), the moved objects after a step (`frame` > 0).
void requireFiniteBoxes(const WorldState& state, uint32_t frame);

// The point at `distance` along a closed path, and the unit direction of travel there.
glm::dvec3 pointOnPath(const MotionPath& path, double distance, glm::dvec3* direction);
MotionPath makePath(std::vector<glm::dvec3> points);
// The rotation about y that turns a model's front (+x) along `direction`: how a model placed
// on a path, or moving on one, faces its travel.
glm::quat yawTowards(const glm::dvec3& direction);

}  // namespace occsim
