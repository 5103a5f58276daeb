// The world in motion: the paths movers follow, the state a run starts from, and one step of
// every mover (and of the glTF models' animations).
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "sim/world/model_copies.h"
#include "sim/world/world.h"

namespace occsim {
namespace {}  // namespace

MotionPath makePath(std::vector<glm::dvec3> points) {
    MotionPath path;
    path.points = std::move(points);
    path.lengths.push_back(0.0);
    const size_t n = path.points.size();
    for (size_t i = 0; i < n; ++i) {
        path.lengths.push_back(path.lengths.back() +
                               glm::length(path.points[(i + 1) % n] - path.points[i]));
    }
    return path;
}

glm::dvec3 pointOnPath(const MotionPath& path, double distance, glm::dvec3* direction) {
    const size_t n = path.points.size();
    const double total = path.total();
    if (n == 1 || !(total > 0.0)) {
        if (direction) *direction = glm::dvec3(1, 0, 0);
        return path.points.front();
    }
    double d = std::fmod(distance, total);
    if (d < 0) d += total;
    const auto it = std::upper_bound(path.lengths.begin(), path.lengths.end(), d);
    const size_t i = std::min(static_cast<size_t>(it - path.lengths.begin()) - 1, n - 1);
    const glm::dvec3 a = path.points[i], b = path.points[(i + 1) % n];
    const double segment = path.lengths[i + 1] - path.lengths[i];
    const double t = segment > 0 ? (d - path.lengths[i]) / segment : 0.0;
    if (direction) *direction = segment > 0 ? (b - a) / segment : glm::dvec3(1, 0, 0);
    return a + t * (b - a);
}

glm::quat yawTowards(const glm::dvec3& direction) {
    // Models face +x (the teapot's spout); yaw about y so +x points along the travel direction.
    const double yaw = std::atan2(-direction.z, direction.x);
    return glm::angleAxis(static_cast<float>(yaw), glm::vec3(0, 1, 0));
}

WorldState initialState(const Scene& scene) {
    WorldState state;
    state.poses = scene.initial_poses;
    state.movers = scene.initial_movers;
    state.copies = scene.initial_copies;
    state.moved = movedObjects(scene, state.movers, state.copies);
    state.pose_buffers = makePoseBuffers(scene.models);
    state.boxes.resize(scene.objectCount());
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        state.boxes[o] =
            worldBox(scene.mesh_bounds[scene.object_mesh[o]], state.poses[o], scene.culling_origin);
    }
    return state;
}

namespace {

void reflectInto(double& position, double& velocity, double lo, double hi) {
    if (!(hi > lo)) {
        position = lo;
        return;
    }
    // Fold the position back into [lo, hi] however far it went (large dt, fast movers): a
    // triangle wave; an odd number of reflections reverses the velocity.
    const double span = hi - lo;
    const double t = (position - lo) / span;
    const double k = std::floor(t);
    const double frac = t - k;
    const bool odd = std::fmod(std::abs(k), 2.0) == 1.0;
    position = lo + span * (odd ? 1.0 - frac : frac);
    if (odd) velocity = -velocity;
}

}  // namespace

void stepMovers(const Scene& scene, WorldState& state, double dt_s) {
    state.time_s += dt_s;
    for (Mover& mover : state.movers) {
        ObjectPose& pose = mover.copy >= 0 ? state.copies[static_cast<size_t>(mover.copy)].anchor
                                           : state.poses[mover.object];
        if (auto* bounce = std::get_if<BounceMotion>(&mover.motion)) {
            pose.position += bounce->velocity * dt_s;
            for (int axis = 0; axis < 3; ++axis) {
                reflectInto(pose.position[axis], bounce->velocity[axis], bounce->region.min[axis],
                            bounce->region.max[axis]);
            }
        } else if (auto* orbit = std::get_if<OrbitMotion>(&mover.motion)) {
            orbit->angle =
                std::remainder(orbit->angle + orbit->angular_speed * dt_s, 2.0 * std::numbers::pi);
            pose.position.x = orbit->center.x + orbit->radius_m * std::cos(orbit->angle);
            pose.position.z = orbit->center.z + orbit->radius_m * std::sin(orbit->angle);
        } else if (auto* path = std::get_if<PathMotion>(&mover.motion)) {
            const MotionPath& p = scene.paths[path->path];
            // Keep the distance within one lap so it never loses precision on long runs.
            path->distance_m = std::fmod(path->distance_m + path->speed_mps * dt_s,
                                         p.total() > 0 ? p.total() : 1.0);
            glm::dvec3 direction;
            pose.position = pointOnPath(p, path->distance_m, &direction);
            pose.rotation = yawTowards(direction);
        } else if (auto* walk = std::get_if<RandomWalkMotion>(&mover.motion)) {
            walk->heading = std::remainder(
                walk->heading + walk->turn_rate * dt_s * walk->rng.uniform(-1.0, 1.0),
                2.0 * std::numbers::pi);
            double vx = walk->speed_mps * std::cos(walk->heading);
            double vz = walk->speed_mps * std::sin(walk->heading);
            pose.position.x += vx * dt_s;
            pose.position.z += vz * dt_s;
            reflectInto(pose.position.x, vx, walk->region.min.x, walk->region.max.x);
            reflectInto(pose.position.z, vz, walk->region.min.z, walk->region.max.z);
            walk->heading = std::atan2(vz, vx);
            pose.rotation = yawTowards({vx, 0.0, vz});
        } else if (auto* spin = std::get_if<SpinMotion>(&mover.motion)) {
            spin->angle =
                std::remainder(spin->angle + spin->angular_speed * dt_s, 2.0 * std::numbers::pi);
            pose.rotation =
                glm::angleAxis(static_cast<float>(spin->angle), glm::vec3(0, 1, 0)) * spin->base;
        }
        if (mover.copy < 0) {
            state.boxes[mover.object] = worldBox(scene.mesh_bounds[scene.object_mesh[mover.object]],
                                                 pose, scene.culling_origin);
        }
    }
    if (!state.copies.empty()) {
        poseCopies(scene, state.time_s, state.copies, state.pose_buffers, state.poses,
                   &state.boxes);
    }
}

}  // namespace occsim
