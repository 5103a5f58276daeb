#include "sim/world/world.h"

#include "sim/scene/primitives.h"
#include "sim/scene/scene_source.h"
#include "sim/scene/teapot.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <numbers>
#include <numeric>

namespace occsim {
namespace {

constexpr double kPi = std::numbers::pi;
enum SeedPurpose : uint64_t { kPlacement = 1, kMoverPick = 2, kMoverMotion = 3, kSpawn = 4 };
constexpr uint32_t kSpawnTeapotTessellation = 4;

// Where a source's content went in the scene.
struct SourceRange {
    uint32_t first = 0;
    uint32_t count = 0;
    Aabb region;
    std::vector<uint32_t> lanes;  // indices into Scene::paths
};

uint32_t addMesh(Scene& scene, MeshData mesh) {
    scene.mesh_bounds.push_back(meshBounds(mesh));
    scene.meshes.push_back(std::move(mesh));
    return static_cast<uint32_t>(scene.meshes.size() - 1);
}

uint32_t addObject(Scene& scene, uint32_t mesh, const ObjectPose& pose) {
    scene.object_mesh.push_back(mesh);
    scene.initial_poses.push_back(pose);
    scene.triangle_count += scene.meshes[mesh].triangleCount();
    return scene.objectCount() - 1;
}

SourceRange addSource(Scene& scene, SourceOutput source) {
    SourceRange range{scene.objectCount(), static_cast<uint32_t>(source.objects.size()), source.region, {}};
    const auto first_mesh = static_cast<uint32_t>(scene.meshes.size());
    for (MeshData& mesh : source.meshes) addMesh(scene, std::move(mesh));
    for (const PlacedObject& o : source.objects) {
        ObjectPose pose;
        pose.position = o.position;
        pose.linear = o.linear;
        addObject(scene, first_mesh + o.mesh, pose);
    }
    if (isEmpty(range.region)) {
        for (uint32_t i = range.first; i < scene.objectCount(); ++i) {
            extend(range.region, worldBox(scene.mesh_bounds[scene.object_mesh[i]], scene.initial_poses[i]));
        }
    }
    for (auto& lane : source.lanes) {
        if (lane.size() < 2) continue;
        range.lanes.push_back(static_cast<uint32_t>(scene.paths.size()));
        scene.paths.push_back(makePath(std::move(lane)));
    }
    for (std::string& w : source.warnings) scene.warnings.push_back(std::move(w));
    return range;
}

// Picks round(fraction * count) distinct objects of the range that do not move yet (partial
// Fisher-Yates; fewer when not enough are left), sorted.
std::vector<uint32_t> pickFraction(const SourceRange& range, double fraction, Rng& rng,
                                   const std::vector<uint8_t>& moving) {
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
    return ids;
}

MeshData spawnMesh(SpawnShape shape) {
    switch (shape) {
        case SpawnShape::Teapot: return tessellateTeapot(kSpawnTeapotTessellation);
        case SpawnShape::Box: return makeBox(glm::vec3(1.0f));
        case SpawnShape::Sphere: return makeSphere(0.5f, 16, 8);
    }
    return {};
}

glm::dvec3 randomPointIn(const Aabb& region, Rng& rng) {
    return {rng.uniform(region.min.x, region.max.x), rng.uniform(region.min.y, region.max.y),
            rng.uniform(region.min.z, region.max.z)};
}

// The distance along `path` of the point nearest to p (so selected objects join a path where
// they stand).
double nearestDistanceOnPath(const MotionPath& path, const glm::dvec3& p) {
    double best = 0.0, best_d2 = INFINITY;
    const size_t n = path.points.size();
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 a = path.points[i], b = path.points[(i + 1) % n];
        const glm::dvec3 ab = b - a;
        const double len2 = glm::dot(ab, ab);
        const double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
        const glm::dvec3 q = a + t * ab;
        const double d2 = glm::dot(p - q, p - q);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = path.lengths[i] + t * (path.lengths[i + 1] - path.lengths[i]);
        }
    }
    return best;
}

glm::quat yawTowards(const glm::dvec3& direction) {
    // Models face +x (the teapot's spout); yaw about y so +x points along the travel direction.
    const double yaw = std::atan2(-direction.z, direction.x);
    return glm::angleAxis(static_cast<float>(yaw), glm::vec3(0, 1, 0));
}

[[noreturn]] void moverError(const Scenario& s, size_t m, const std::string& key, const std::string& message) {
    throw ScenarioError(s.file.string(), "/movers/" + std::to_string(m) + (key.empty() ? "" : "/" + key), message);
}

// The centre of the initial scene's bounds, rounded to whole metres (so that a scene moved by
// whole metres gets an origin moved by exactly as much). Non-finite placements are left out;
// they are reported when the run starts.
glm::dvec3 cullingOriginOf(const Scene& scene) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        const glm::dvec3& p = scene.initial_poses[o].position;
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) continue;
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    if (!(lo.x <= hi.x)) return glm::dvec3(0.0);
    return glm::round(0.5 * lo + 0.5 * hi);
}

}  // namespace

MotionPath makePath(std::vector<glm::dvec3> points) {
    MotionPath path;
    path.points = std::move(points);
    path.lengths.push_back(0.0);
    const size_t n = path.points.size();
    for (size_t i = 0; i < n; ++i) {
        path.lengths.push_back(path.lengths.back() + glm::length(path.points[(i + 1) % n] - path.points[i]));
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

Scene buildScene(const Scenario& scenario) {
    Scene scene;
    std::vector<SourceRange> ranges;
    for (size_t s = 0; s < scenario.sources.size(); ++s) {
        ranges.push_back(addSource(scene, generateSource(scenario.sources[s], deriveSeed(scenario.seed, s, kPlacement))));
    }
    std::vector<uint8_t> moving(scene.objectCount(), 0);  // an object gets one motion at most
    for (size_t m = 0; m < scenario.movers.size(); ++m) {
        const MoverSpec& spec = scenario.movers[m];
        const SourceRange& range = ranges.at(spec.source);
        Rng pick(deriveSeed(scenario.seed, m, kMoverPick));
        Rng motion(deriveSeed(scenario.seed, m, kMoverMotion));
        const Aabb region = spec.has_region ? spec.region : range.region;

        // The paths this mover's objects follow.
        std::vector<uint32_t> paths = range.lanes;
        if (spec.motion == MotionType::Path) {
            if (!spec.waypoints.empty()) {
                paths = {static_cast<uint32_t>(scene.paths.size())};
                scene.paths.push_back(makePath(spec.waypoints));
            } else if (paths.empty()) {
                moverError(scenario, m, "motion", "motion \"path\" needs 'waypoints': source " +
                                                      std::to_string(spec.source) + " has no lanes");
            }
        }

        // The objects: picked from the source, listed, or spawned.
        std::vector<uint32_t> objects;
        if (spec.selection == MoverSelection::Fraction) {
            objects = pickFraction(range, spec.fraction, pick, moving);
        } else if (spec.selection == MoverSelection::Objects) {
            for (size_t i = 0; i < spec.objects.size(); ++i) {
                checkMoverObjectIndex(scenario, m, i, range.count);
                const uint32_t local = spec.objects[i];
                if (moving[range.first + local]) {
                    moverError(scenario, m, "objects/" + std::to_string(i),
                               "object " + std::to_string(local) + " already has a motion");
                }
                objects.push_back(range.first + local);
            }
        } else {
            Rng spawn(deriveSeed(scenario.seed, m, kSpawn));
            const uint32_t mesh = addMesh(scene, spawnMesh(spec.spawn.shape));
            for (uint32_t i = 0; i < spec.spawn.count; ++i) {
                ObjectPose pose;
                pose.position = randomPointIn(region, spawn);
                pose.linear = glm::mat3(static_cast<float>(spawn.uniform(spec.spawn.size_min_m, spec.spawn.size_max_m)));
                objects.push_back(addObject(scene, mesh, pose));
            }
            moving.resize(scene.objectCount(), 0);
        }

        for (uint32_t object : objects) {
            moving[object] = 1;
            ObjectPose& pose = scene.initial_poses[object];
            const double speed = motion.uniform(spec.speed_min_mps, spec.speed_max_mps);
            Mover mover{object, BounceMotion{}};
            switch (spec.motion) {
                case MotionType::Bounce: {
                    // Mostly horizontal, like traffic; a little vertical drift where the box allows.
                    const double a = motion.uniform(0.0, 2.0 * kPi);
                    const glm::dvec3 dir(std::cos(a), motion.uniform(-0.2, 0.2), std::sin(a));
                    mover.motion = BounceMotion{speed * glm::normalize(dir), region};
                    break;
                }
                case MotionType::Orbit: {
                    const double radius = motion.uniform(spec.radius_min_m, spec.radius_max_m);
                    const double angle = motion.uniform(0.0, 2.0 * kPi);
                    const double sign = motion.uniform() < 0.5 ? -1.0 : 1.0;
                    // Centre chosen so that the orbit passes through the object's start position.
                    const glm::dvec3 center = pose.position - radius * glm::dvec3(std::cos(angle), 0, std::sin(angle));
                    mover.motion = OrbitMotion{center, radius, sign * speed / radius, angle};
                    break;
                }
                case MotionType::Path: {
                    const uint32_t path = paths[pick.below(static_cast<uint32_t>(paths.size()))];
                    const MotionPath& p = scene.paths[path];
                    const double distance = spec.selection == MoverSelection::Spawn
                                                ? motion.uniform(0.0, p.total())
                                                : nearestDistanceOnPath(p, pose.position);
                    mover.motion = PathMotion{path, distance, speed};
                    glm::dvec3 direction;
                    pose.position = pointOnPath(p, distance, &direction);
                    pose.rotation = yawTowards(direction);
                    break;
                }
                case MotionType::RandomWalk: {
                    RandomWalkMotion walk;
                    walk.speed_mps = speed;
                    walk.heading = motion.uniform(0.0, 2.0 * kPi);
                    walk.turn_rate = glm::radians(spec.turn_rate_deg_s);
                    walk.region = region;
                    walk.rng = Rng(motion.next());
                    mover.motion = walk;
                    break;
                }
                case MotionType::Spin: {
                    const double rate = glm::radians(motion.uniform(spec.spin_min_deg_s, spec.spin_max_deg_s));
                    mover.motion = SpinMotion{motion.uniform() < 0.5 ? -rate : rate, 0.0, pose.rotation};
                    break;
                }
            }
            scene.initial_movers.push_back(mover);
        }
    }
    scene.culling_origin = cullingOriginOf(scene);
    return scene;
}

WorldState initialState(const Scene& scene) {
    WorldState state;
    state.poses = scene.initial_poses;
    state.movers = scene.initial_movers;
    state.boxes.resize(scene.objectCount());
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        state.boxes[o] = worldBox(scene.mesh_bounds[scene.object_mesh[o]], state.poses[o],
                                  scene.culling_origin);
    }
    return state;
}

glm::dmat4 modelMatrix(const ObjectPose& pose) {
    return glm::translate(glm::dmat4(1.0), pose.position) * glm::dmat4(glm::mat4_cast(pose.rotation)) *
           glm::dmat4(glm::mat4(pose.linear));
}

namespace {

// Float conversions that never move a bound inward.
float floatAtMost(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return f;
}

float floatAtLeast(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}

}  // namespace

Aabb worldBox(const Aabb& mesh_bounds, const ObjectPose& pose, const glm::dvec3& origin) {
    // Arvo's transform of the local box by the linear part, in double, then the position relative
    // to the origin: exact to double precision, and only then rounded (outward) to float.
    ObjectPose at_origin = pose;
    at_origin.position = glm::dvec3(0.0);
    const glm::dmat4 m = modelMatrix(at_origin);
    glm::dvec3 lo = pose.position - origin, hi = lo;
    for (int col = 0; col < 3; ++col) {
        for (int row = 0; row < 3; ++row) {
            const double a = m[col][row] * mesh_bounds.min[col];
            const double b = m[col][row] * mesh_bounds.max[col];
            lo[row] += std::min(a, b);
            hi[row] += std::max(a, b);
        }
    }
    Aabb box;
    for (int axis = 0; axis < 3; ++axis) {
        box.min[axis] = floatAtMost(lo[axis]);
        box.max[axis] = floatAtLeast(hi[axis]);
    }
    return box;
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
            orbit->angle = std::remainder(orbit->angle + orbit->angular_speed * dt_s, 2.0 * kPi);
            pose.position.x = orbit->center.x + orbit->radius_m * std::cos(orbit->angle);
            pose.position.z = orbit->center.z + orbit->radius_m * std::sin(orbit->angle);
        } else if (auto* path = std::get_if<PathMotion>(&mover.motion)) {
            const MotionPath& p = scene.paths[path->path];
            // Keep the distance within one lap so it never loses precision on long runs.
            path->distance_m = std::fmod(path->distance_m + path->speed_mps * dt_s, p.total() > 0 ? p.total() : 1.0);
            glm::dvec3 direction;
            pose.position = pointOnPath(p, path->distance_m, &direction);
            pose.rotation = yawTowards(direction);
        } else if (auto* walk = std::get_if<RandomWalkMotion>(&mover.motion)) {
            walk->heading = std::remainder(
                walk->heading + walk->turn_rate * dt_s * walk->rng.uniform(-1.0, 1.0), 2.0 * kPi);
            double vx = walk->speed_mps * std::cos(walk->heading);
            double vz = walk->speed_mps * std::sin(walk->heading);
            pose.position.x += vx * dt_s;
            pose.position.z += vz * dt_s;
            reflectInto(pose.position.x, vx, walk->region.min.x, walk->region.max.x);
            reflectInto(pose.position.z, vz, walk->region.min.z, walk->region.max.z);
            walk->heading = std::atan2(vz, vx);
            pose.rotation = yawTowards({vx, 0.0, vz});
        } else if (auto* spin = std::get_if<SpinMotion>(&mover.motion)) {
            spin->angle = std::remainder(spin->angle + spin->angular_speed * dt_s, 2.0 * kPi);
            pose.rotation = glm::angleAxis(static_cast<float>(spin->angle), glm::vec3(0, 1, 0)) * spin->base;
        }
        state.boxes[mover.object] =
            worldBox(scene.mesh_bounds[scene.object_mesh[mover.object]], pose, scene.culling_origin);
    }
}

namespace {

[[noreturn]] void throwNotFinite(const WorldState& state, uint32_t object, uint32_t frame,
                                 const std::string& how) {
    const glm::dvec3& p = state.poses[object].position;
    char position[160];
    std::snprintf(position, sizeof position, "(%g, %g, %g)", p.x, p.y, p.z);
    throw MotionError("frame " + std::to_string(frame) + ": object " + std::to_string(object) +
                      " " + how + " left finite float coordinates (its position is " + position +
                      "); the run stops here");
}

}  // namespace

void requireFiniteBoxes(const WorldState& state, uint32_t frame) {
    if (frame == 0) {
        for (uint32_t o = 0; o < state.boxes.size(); ++o) {
            if (!isFiniteAndOrdered(state.boxes[o])) throwNotFinite(state, o, frame, "as placed");
        }
        return;
    }
    for (size_t m = 0; m < state.movers.size(); ++m) {
        const uint32_t o = state.movers[m].object;
        if (!isFiniteAndOrdered(state.boxes[o])) {
            throwNotFinite(state, o, frame, "moved by mover " + std::to_string(m));
        }
    }
}

}  // namespace occsim
