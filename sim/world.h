// The simulated world: immutable scene content (meshes, which mesh each object draws, the initial
// poses, the movers' starting state) built once from a scenario, and the per-run mutable state
// (poses, world boxes, movers) that each simulation owns a copy of, so that several algorithms can
// run the same frames side by side.
#pragma once

#include "culling/aabb.h"
#include "render/mesh_data.h"
#include "sim/scenario.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <variant>
#include <vector>

namespace occsim {

// Positions in double: scenes may sit far from the origin; rendering is camera-relative.
struct ObjectPose {
    glm::dvec3 position{0.0};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    float scale = 1.0f;
};

// Straight line at constant velocity, reflected at the region's faces (object position).
struct BounceMotion {
    glm::dvec3 velocity{0.0};
    Aabb region;
};

// Circle around a vertical axis through `center`, at constant speed.
struct OrbitMotion {
    glm::dvec3 center{0.0};
    double radius_m = 1.0;
    double angular_speed = 0.0;  // radians per second (signed)
    double angle = 0.0;
};

struct Mover {
    uint32_t object = 0;
    std::variant<BounceMotion, OrbitMotion> motion;
};

struct Scene {
    std::vector<MeshData> meshes;
    std::vector<Aabb> mesh_bounds;      // model space, per mesh
    std::vector<uint32_t> object_mesh;  // per object
    std::vector<ObjectPose> initial_poses;
    std::vector<Mover> initial_movers;
    uint64_t triangle_count = 0;        // over all objects

    uint32_t objectCount() const { return static_cast<uint32_t>(object_mesh.size()); }
};

struct WorldState {
    std::vector<ObjectPose> poses;
    std::vector<Aabb> boxes;  // world space, float
    std::vector<Mover> movers;
};

// Builds the scene a scenario describes; deterministic for a given scenario (and its seed).
Scene buildScene(const Scenario& scenario);

WorldState initialState(const Scene& scene);

glm::dmat4 modelMatrix(const ObjectPose& pose);
Aabb worldBox(const Aabb& mesh_bounds, const ObjectPose& pose);

// Advances every mover by dt seconds and refreshes the world boxes of the objects it moved.
void stepMovers(const Scene& scene, WorldState& state, double dt_s);

}  // namespace occsim
