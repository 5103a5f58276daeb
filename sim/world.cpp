#include "sim/world.h"

#include "sim/rng.h"
#include "sim/teapot.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace occsim {
namespace {

enum SeedPurpose : uint64_t { kPlacement = 1, kMoverPick = 2, kMoverMotion = 3 };

// A source's objects occupy a contiguous range of object indices.
struct SourceRange {
    uint32_t first = 0;
    uint32_t count = 0;
    Aabb region;
};

SourceRange addTeapotField(const TeapotFieldSpec& spec, uint64_t seed, Scene& scene) {
    const uint32_t mesh = static_cast<uint32_t>(scene.meshes.size());
    scene.meshes.push_back(tessellateTeapot(spec.tessellation));
    scene.mesh_bounds.push_back(meshBounds(scene.meshes.back()));
    SourceRange range{scene.objectCount(), spec.count, spec.region};
    Rng rng(seed);
    const glm::dvec3 lo(spec.region.min), hi(spec.region.max);
    for (uint32_t i = 0; i < spec.count; ++i) {
        ObjectPose pose;
        pose.position = {rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z)};
        const double yaw = rng.uniform(0.0, 2.0 * std::numbers::pi);
        pose.rotation = glm::angleAxis(static_cast<float>(yaw), glm::vec3(0, 1, 0));
        pose.scale = static_cast<float>(rng.uniform(spec.size_min_m, spec.size_max_m));
        scene.object_mesh.push_back(mesh);
        scene.initial_poses.push_back(pose);
    }
    scene.triangle_count += uint64_t{spec.count} * scene.meshes[mesh].triangleCount();
    return range;
}

// Picks round(fraction * count) distinct objects of the range that do not move yet (partial
// Fisher-Yates; fewer when not enough are left), sorted, and marks them as moving.
std::vector<uint32_t> pickObjects(const SourceRange& range, double fraction, Rng& rng,
                                  std::vector<uint8_t>& moving) {
    std::vector<uint32_t> ids;
    for (uint32_t o = range.first; o < range.first + range.count; ++o) {
        if (!moving[o]) ids.push_back(o);
    }
    const auto free_count = static_cast<uint32_t>(ids.size());
    const auto wanted =
        std::min(free_count, static_cast<uint32_t>(std::lround(fraction * range.count)));
    for (uint32_t i = 0; i < wanted; ++i) std::swap(ids[i], ids[i + rng.below(free_count - i)]);
    ids.resize(wanted);
    std::sort(ids.begin(), ids.end());
    for (uint32_t o : ids) moving[o] = 1;
    return ids;
}

glm::dvec3 randomHorizontalDirection(Rng& rng) {
    const double a = rng.uniform(0.0, 2.0 * std::numbers::pi);
    return {std::cos(a), 0.0, std::sin(a)};
}

}  // namespace

Scene buildScene(const Scenario& scenario) {
    Scene scene;
    std::vector<SourceRange> ranges;
    for (size_t s = 0; s < scenario.sources.size(); ++s) {
        const SceneSourceSpec& source = scenario.sources[s];
        ranges.push_back(addTeapotField(source.teapots, deriveSeed(scenario.seed, s, kPlacement), scene));
    }
    std::vector<uint8_t> moving(scene.objectCount(), 0);  // an object gets one motion at most
    for (size_t m = 0; m < scenario.movers.size(); ++m) {
        const MoverSpec& spec = scenario.movers[m];
        const SourceRange& range = ranges.at(spec.source);
        Rng pick(deriveSeed(scenario.seed, m, kMoverPick));
        Rng motion(deriveSeed(scenario.seed, m, kMoverMotion));
        for (uint32_t object : pickObjects(range, spec.fraction, pick, moving)) {
            const double speed = motion.uniform(spec.speed_min_mps, spec.speed_max_mps);
            Mover mover{object, BounceMotion{}};
            if (spec.motion == MotionType::Bounce) {
                // Mostly horizontal, like traffic; a little vertical drift where the box allows.
                glm::dvec3 dir = randomHorizontalDirection(motion);
                dir.y = motion.uniform(-0.2, 0.2);
                mover.motion = BounceMotion{speed * glm::normalize(dir),
                                            spec.has_region ? spec.region : range.region};
            } else {
                const double radius = motion.uniform(spec.radius_min_m, spec.radius_max_m);
                const double angle = motion.uniform(0.0, 2.0 * std::numbers::pi);
                const double direction = motion.uniform() < 0.5 ? -1.0 : 1.0;
                const glm::dvec3 start = scene.initial_poses[object].position;
                // Centre chosen so that the orbit passes through the object's start position.
                const glm::dvec3 center = start - radius * glm::dvec3(std::cos(angle), 0, std::sin(angle));
                mover.motion = OrbitMotion{center, radius, direction * speed / radius, angle};
            }
            scene.initial_movers.push_back(mover);
        }
    }
    return scene;
}

WorldState initialState(const Scene& scene) {
    WorldState state;
    state.poses = scene.initial_poses;
    state.movers = scene.initial_movers;
    state.boxes.resize(scene.objectCount());
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        state.boxes[o] = worldBox(scene.mesh_bounds[scene.object_mesh[o]], state.poses[o]);
    }
    return state;
}

glm::dmat4 modelMatrix(const ObjectPose& pose) {
    return glm::translate(glm::dmat4(1.0), pose.position) * glm::dmat4(glm::mat4_cast(pose.rotation)) *
           glm::scale(glm::dmat4(1.0), glm::dvec3(pose.scale));
}

Aabb worldBox(const Aabb& mesh_bounds, const ObjectPose& pose) {
    return transformAabb(mesh_bounds, glm::mat4(modelMatrix(pose)));
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
    for (Mover& mover : state.movers) {
        ObjectPose& pose = state.poses[mover.object];
        if (auto* bounce = std::get_if<BounceMotion>(&mover.motion)) {
            pose.position += bounce->velocity * dt_s;
            for (int axis = 0; axis < 3; ++axis) {
                reflectInto(pose.position[axis], bounce->velocity[axis], bounce->region.min[axis],
                            bounce->region.max[axis]);
            }
        } else if (auto* orbit = std::get_if<OrbitMotion>(&mover.motion)) {
            orbit->angle = std::remainder(orbit->angle + orbit->angular_speed * dt_s,
                                          2.0 * std::numbers::pi);
            pose.position.x = orbit->center.x + orbit->radius_m * std::cos(orbit->angle);
            pose.position.z = orbit->center.z + orbit->radius_m * std::sin(orbit->angle);
        }
        state.boxes[mover.object] = worldBox(scene.mesh_bounds[scene.object_mesh[mover.object]], pose);
    }
}

}  // namespace occsim
