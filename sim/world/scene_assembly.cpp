// buildScene(): a scenario's sources and movers assembled into the Scene a run starts from.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <numbers>
#include <numeric>

#include "sim/scene/primitives.h"
#include "sim/scene/scene_source.h"
#include "sim/scene/teapot.h"
#include "sim/world/model_copies.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

enum SeedPurpose : uint64_t {
    kPlacement = 1,
    kMoverPick = 2,
    kMoverMotion = 3,
    kSpawn = 4,
    kAnimationPhase = 5,
};
constexpr uint32_t kSpawnTeapotTessellation = 4;

// Where a source's content went in the scene.
struct SourceRange {
    uint32_t first = 0;
    uint32_t count = 0;
    WorldBox region;
    std::vector<uint32_t> lanes;  // indices into Scene::paths
    // glTF sources: the model (index into Scene::models), where each copy went, and each copy's
    // index into Scene::initial_copies once it moves (-1 while it stands still).
    int32_t model = -1;
    std::vector<ModelCopyPlacement> placements;
    std::vector<int32_t> copy_state;
};

// What a generated object is called, after its source: "teapot 17".
std::string sourceKindName(SourceType type) {
    switch (type) {
        case SourceType::Teapots:
            return "teapot";
        case SourceType::Gltf:
            return "gltf object";
        case SourceType::City:
            return "city part";
        case SourceType::Library:
            return "library part";
        case SourceType::Plant:
            return "plant part";
    }
    return "object";
}

uint32_t addMesh(Scene& scene, MeshData mesh) {
    scene.mesh_bounds.push_back(meshBounds(mesh));
    scene.meshes.push_back(std::move(mesh));
    return static_cast<uint32_t>(scene.meshes.size() - 1);
}

uint32_t addObject(Scene& scene, uint32_t mesh, const ObjectPose& pose, std::string name,
                   OccluderRole occluder, uint32_t occluder_mesh = kNoAuthoredOccluder) {
    scene.object_mesh.push_back(mesh);
    scene.object_names.push_back(std::move(name));
    scene.object_occluder.push_back(occluder);
    scene.object_occluder_mesh.push_back(occluder_mesh);
    scene.initial_poses.push_back(pose);
    scene.triangle_count += scene.meshes[mesh].triangleCount();
    return scene.objectCount() - 1;
}

// A source's meshes and objects into the scene; a glTF source with "place": false adds its meshes
// only (its model is placed by spawning movers). `copy_meshes` gets the meshes of one copy's
// objects, for spawning.
SourceRange addSource(Scene& scene, SourceOutput source, bool place, const std::string& kind,
                      OccluderRole occluders, std::vector<uint32_t>& copy_meshes,
                      std::vector<std::string>& copy_names,
                      std::vector<OccluderRole>& copy_occluders,
                      std::vector<uint32_t>& copy_occluder_meshes) {
    const auto first_mesh = static_cast<uint32_t>(scene.meshes.size());
    const size_t per_copy = source.model ? source.model->object_visit.size() : 0;
    for (size_t j = 0; j < per_copy && j < source.objects.size(); ++j) {
        copy_meshes.push_back(first_mesh + source.objects[j].mesh);
        // Copy 0's names carry " #0" when the model was replicated: spawned copies get theirs.
        const std::string& name = source.objects[j].name;
        const size_t mark = name.rfind(" #");
        copy_names.push_back(per_copy < source.objects.size() && mark != std::string::npos
                                 ? name.substr(0, mark)
                                 : name);
        copy_occluders.push_back(source.objects[j].occluder.value_or(occluders));
        const std::optional<uint32_t>& authored = source.objects[j].occluder_mesh;
        copy_occluder_meshes.push_back(authored ? first_mesh + *authored : kNoAuthoredOccluder);
    }
    if (!place) {
        source.objects.clear();
        source.model_copies.clear();
        source.lanes.clear();
    }
    SourceRange range{scene.objectCount(),
                      static_cast<uint32_t>(source.objects.size()),
                      source.region,
                      {},
                      -1,
                      {},
                      {}};
    range.placements = std::move(source.model_copies);
    range.copy_state.assign(range.placements.size(), -1);
    for (MeshData& mesh : source.meshes) addMesh(scene, std::move(mesh));
    for (size_t i = 0; i < source.objects.size(); ++i) {
        const PlacedObject& o = source.objects[i];
        ObjectPose pose;
        pose.position = o.position;
        pose.linear = o.linear;
        addObject(scene, first_mesh + o.mesh, pose,
                  o.name.empty() ? kind + " " + std::to_string(i) : o.name,
                  o.occluder.value_or(occluders),
                  o.occluder_mesh ? first_mesh + *o.occluder_mesh : kNoAuthoredOccluder);
    }
    if (isEmpty(range.region)) {
        for (uint32_t i = range.first; i < scene.objectCount(); ++i) {
            extend(range.region,
                   worldBox(scene.mesh_bounds[scene.object_mesh[i]], scene.initial_poses[i]));
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

[[noreturn]] void sourceError(const Scenario& s, size_t source, const std::string& key,
                              const std::string& message) {
    throw ScenarioError(s.file.string(), "/scene/sources/" + std::to_string(source) + "/" + key,
                        message);
}

// Which animations of source s's model play (its "animation" keys), and what they move.
SceneModel makeSceneModel(const Scenario& scenario, size_t s,
                          std::shared_ptr<const AnimatedModel> model) {
    const GltfSourceSpec& gltf = std::get<GltfSourceSpec>(scenario.sources[s].spec);
    const GltfAnimationSpec& spec = gltf.animation;
    SceneModel m;
    m.source = static_cast<uint32_t>(s);
    m.speed = spec.speed;
    m.mode = spec.mode;
    m.time_offset_s = spec.time_offset_s;
    const size_t count = model->animations.size();
    m.playing.assign(count, spec.play_all ? 1 : 0);
    for (size_t j = 0; j < spec.play.size(); ++j) {
        const AnimationPick& pick = spec.play[j];
        const std::string key = "animation/play/" + std::to_string(j);
        size_t a = pick.index;
        if (!pick.name.empty()) {
            std::string names;
            for (a = 0; a < count && model->animations[a].name != pick.name; ++a) {
            }
            if (a == count) {
                for (const NodeAnimation& animation : model->animations) {
                    if (!names.empty()) names += ", ";
                    names += "'";
                    names += animation.name;
                    names += "'";
                }
                sourceError(scenario, s, key,
                            "no animation named '" + pick.name + "' in " + gltf.path.string() +
                                " (it has " + (count == 0 ? std::string("none") : names) + ")");
            }
        } else if (a >= count) {
            sourceError(scenario, s, key,
                        "expected an animation index < " + std::to_string(count) + " (" +
                            gltf.path.string() + " has " + std::to_string(count) + "), got " +
                            std::to_string(a));
        }
        m.playing[a] = 1;
    }
    m.object_animated.assign(model->object_visit.size(), 0);
    for (size_t a = 0; a < count; ++a) {
        if (!m.playing[a]) continue;
        const std::vector<uint8_t> moved = model->objectsMovedBy(a);
        for (size_t o = 0; o < moved.size(); ++o) m.object_animated[o] |= moved[o];
    }
    m.model = std::move(model);
    return m;
}

double longestPlayingDuration(const SceneModel& m) {
    double longest = 0.0;
    for (size_t a = 0; a < m.playing.size(); ++a) {
        if (m.playing[a]) longest = std::max(longest, m.model->animations[a].duration_s);
    }
    return longest;
}

bool animatesSomething(const SceneModel& m) {
    return std::any_of(m.object_animated.begin(), m.object_animated.end(),
                       [](uint8_t a) { return a != 0; });
}

// The anchor of a copy placed by its source: T(origin) · R_y(yaw).
ObjectPose anchorOf(const ModelCopyPlacement& placement) {
    ObjectPose anchor;
    anchor.position = placement.origin;
    anchor.linear = glm::mat3(glm::rotate(glm::dmat4(1.0), placement.yaw, glm::dvec3(0, 1, 0)));
    return anchor;
}

// Copy k of a glTF source's range as a moving copy (made on first use).
uint32_t movingCopy(Scene& scene, SourceRange& range, uint32_t k) {
    if (range.copy_state[k] < 0) {
        ModelCopy copy;
        copy.model = static_cast<uint32_t>(range.model);
        copy.first_object = range.first + k * scene.models[copy.model].objectsPerCopy();
        copy.anchor = anchorOf(range.placements[k]);
        range.copy_state[k] = static_cast<int32_t>(scene.initial_copies.size());
        scene.initial_copies.push_back(copy);
    }
    return static_cast<uint32_t>(range.copy_state[k]);
}

// Every copy of an animated model moves by its animations, each at its own seeded phase when
// the source asks for one.
void animateCopies(Scene& scene, const Scenario& scenario, size_t s, SourceRange& range) {
    const SceneModel& m = scene.models[static_cast<size_t>(range.model)];
    if (!animatesSomething(m)) return;
    const GltfAnimationSpec& spec = std::get<GltfSourceSpec>(scenario.sources[s].spec).animation;
    Rng phase(deriveSeed(scenario.seed, s, kAnimationPhase));
    const double longest = longestPlayingDuration(m);
    for (uint32_t k = 0; k < range.placements.size(); ++k) {
        ModelCopy& copy = scene.initial_copies[movingCopy(scene, range, k)];
        copy.animated = true;
        if (spec.random_phase) copy.phase_s = phase.uniform(0.0, longest);
    }
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
        case SpawnShape::Teapot:
            return tessellateTeapot(kSpawnTeapotTessellation);
        case SpawnShape::Box:
            return makeBox(glm::vec3(1.0f));
        case SpawnShape::Sphere:
            return makeSphere(0.5f, 16, 8);
    }
    return {};
}

glm::dvec3 randomPointIn(const WorldBox& region, Rng& rng) {
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

[[noreturn]] void moverError(const Scenario& s, size_t m, const std::string& key,
                             const std::string& message) {
    throw ScenarioError(s.file.string(),
                        "/movers/" + std::to_string(m) + (key.empty() ? "" : "/" + key), message);
}

// The centre of the initial scene's bounds, rounded to whole metres (so that a scene moved by
// whole metres gets an origin moved by exactly as much). Non-finite placements are left out;
// they are reported when the run starts.
// The centre of the camera path's keyframe positions, rounded to whole metres: float precision
// in the culling frame is finest where the camera looks from, whatever else the scene holds. The
// centre of the objects' initial positions (the rule before) let a far-away object, a mover
// spawned along a path that reaches 10^9 m, or a node 10^6 m away pull the origin, and with it
// the eye and frustum the cullers see, into coordinates where a float steps by metres.
glm::dvec3 cullingOriginOf(const CameraSpec& camera) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const CameraKeyframe& key : camera.keyframes) {
        const glm::dvec3& p = key.position;
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) continue;
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    if (!(lo.x <= hi.x)) return glm::dvec3(0.0);
    return glm::round(0.5 * lo + 0.5 * hi);
}

// A whole-copy mover's copies: a share of the source's copies that move neither whole nor by an
// object mover of their own, or the listed copy indices. Each is made a rigid moving copy.
void pickWholeCopies(Scene& scene, const Scenario& scenario, size_t m, SourceRange& range,
                     Rng& pick, std::vector<uint8_t>& moving, const std::vector<uint8_t>& own_mover,
                     std::vector<uint8_t>& rigid_copy, std::vector<uint32_t>& objects,
                     std::vector<int32_t>& object_copy) {
    const MoverSpec& spec = scenario.movers[m];
    const auto copy_count = static_cast<uint32_t>(range.placements.size());
    const uint32_t per_copy = copy_count ? range.count / copy_count : 0;
    auto rigid = [&](uint32_t k) {
        const int32_t state = range.copy_state[k];
        return state >= 0 && static_cast<size_t>(state) < rigid_copy.size() &&
               rigid_copy[static_cast<size_t>(state)];
    };
    auto hasObjectMover = [&](uint32_t k) {
        for (uint32_t j = 0; j < per_copy; ++j) {
            if (own_mover[range.first + k * per_copy + j]) return true;
        }
        return false;
    };
    std::vector<uint32_t> picked;
    if (spec.selection == MoverSelection::Fraction) {
        for (uint32_t k = 0; k < copy_count; ++k) {
            if (!rigid(k) && !hasObjectMover(k)) picked.push_back(k);
        }
        const auto free_count = static_cast<uint32_t>(picked.size());
        const auto wanted =
            std::min(free_count, static_cast<uint32_t>(std::lround(spec.fraction * copy_count)));
        for (uint32_t i = 0; i < wanted; ++i)
            std::swap(picked[i], picked[i + pick.below(free_count - i)]);
        picked.resize(wanted);
        std::sort(picked.begin(), picked.end());
    } else {
        for (size_t i = 0; i < spec.objects.size(); ++i) {
            const uint32_t k = spec.objects[i];
            const std::string key = "objects/" + std::to_string(i);
            if (k >= copy_count) {
                moverError(scenario, m, key,
                           "expected a copy index < " + std::to_string(copy_count) + " (source " +
                               std::to_string(spec.source) +
                               "'s copies, with \"whole_copies\"), got " + std::to_string(k));
            }
            if (rigid(k))
                moverError(scenario, m, key, "copy " + std::to_string(k) + " already has a motion");
            if (hasObjectMover(k)) {
                moverError(
                    scenario, m, key,
                    "an object of copy " + std::to_string(k) + " already has a mover of its own");
            }
            picked.push_back(k);
        }
    }
    for (uint32_t k : picked) {
        const uint32_t index = movingCopy(scene, range, k);
        rigid_copy.resize(scene.initial_copies.size(), 0);
        rigid_copy[index] = 1;
        ModelCopy& copy = scene.initial_copies[index];
        copy.rigid = true;
        for (uint32_t j = 0; j < per_copy; ++j) moving[copy.first_object + j] = 1;
        objects.push_back(copy.first_object);
        object_copy.push_back(static_cast<int32_t>(index));
    }
}

// Every source's content into the scene, glTF models with their copies' animations.
std::vector<SourceRange> addSources(Scene& scene, const Scenario& scenario) {
    std::vector<SourceRange> ranges;
    for (size_t s = 0; s < scenario.sources.size(); ++s) {
        SourceOutput source =
            generateSource(scenario.sources[s], deriveSeed(scenario.seed, s, kPlacement));
        std::shared_ptr<const AnimatedModel> model = source.model;
        const bool place = !model || std::get<GltfSourceSpec>(scenario.sources[s].spec).place;
        if (place)
            scene.lights.insert(scene.lights.end(), source.lights.begin(), source.lights.end());
        std::vector<uint32_t> copy_meshes;
        std::vector<std::string> copy_names;
        std::vector<OccluderRole> copy_occluders;
        std::vector<uint32_t> copy_occluder_meshes;
        ranges.push_back(addSource(scene, std::move(source), place,
                                   sourceKindName(scenario.sources[s].type),
                                   scenario.sources[s].occluders, copy_meshes, copy_names,
                                   copy_occluders, copy_occluder_meshes));
        if (model) {
            ranges.back().model = static_cast<int32_t>(scene.models.size());
            scene.models.push_back(makeSceneModel(scenario, s, std::move(model)));
            scene.models.back().object_mesh = std::move(copy_meshes);
            scene.models.back().object_names = std::move(copy_names);
            scene.models.back().object_occluder = std::move(copy_occluders);
            scene.models.back().object_occluder_mesh = std::move(copy_occluder_meshes);
            animateCopies(scene, scenario, s, ranges.back());
        }
    }
    return ranges;
}

// An object gets one motion at most: its glTF animation, a mover of its own, or its copy's. Per
// object, grown as movers spawn objects.
struct MotionFlags {
    std::vector<uint8_t> moving, animated, own_mover;
    void grow(size_t objects, uint8_t spawned_moving) {
        moving.resize(objects, spawned_moving);
        animated.resize(objects, 0);
        own_mover.resize(objects, 0);
    }
};

MotionFlags animatedObjects(const Scene& scene) {
    MotionFlags flags;
    flags.grow(scene.objectCount(), 0);
    for (const ModelCopy& copy : scene.initial_copies) {
        const SceneModel& m = scene.models[copy.model];
        for (uint32_t j = 0; j < m.objectsPerCopy(); ++j) {
            if (m.object_animated[j])
                flags.moving[copy.first_object + j] = flags.animated[copy.first_object + j] = 1;
        }
    }
    return flags;
}

// The paths a mover's objects follow (indices into Scene::paths): its waypoints, or its source's
// lanes.
std::vector<uint32_t> moverPaths(Scene& scene, const Scenario& scenario, size_t m,
                                 const SourceRange& range) {
    const MoverSpec& spec = scenario.movers[m];
    std::vector<uint32_t> paths = range.lanes;
    if (spec.motion != MotionType::Path) return paths;
    if (!spec.waypoints.empty()) {
        paths = {static_cast<uint32_t>(scene.paths.size())};
        scene.paths.push_back(makePath(spec.waypoints));
    } else if (paths.empty()) {
        moverError(scenario, m, "motion",
                   "motion \"path\" needs 'waypoints': source " + std::to_string(spec.source) +
                       " has no lanes");
    }
    return paths;
}

// The objects a mover moves, and per object the copy it moves whole (-1: the object alone).
struct MoverObjects {
    std::vector<uint32_t> objects;
    std::vector<int32_t> copy;
};

// A spawning mover's new copies of a glTF model, each moved whole.
void spawnModelCopies(Scene& scene, const Scenario& scenario, size_t m,
                      const SourceRange& model_range, const WorldBox& region, MoverObjects& out,
                      MotionFlags& flags) {
    const MoverSpec& spec = scenario.movers[m];
    Rng spawn(deriveSeed(scenario.seed, m, kSpawn));
    const auto model = static_cast<uint32_t>(model_range.model);
    const SceneModel& sm = scene.models[model];
    const GltfAnimationSpec& play =
        std::get<GltfSourceSpec>(scenario.sources[sm.source].spec).animation;
    const double longest = longestPlayingDuration(sm);
    const bool animates = animatesSomething(sm);
    for (uint32_t i = 0; i < spec.spawn.count; ++i) {
        ModelCopy copy;
        copy.model = model;
        copy.first_object = scene.objectCount();
        copy.anchor.position = randomPointIn(region, spawn);
        copy.anchor.linear = glm::mat3(
            static_cast<float>(spawn.uniform(spec.spawn.size_min_m, spec.spawn.size_max_m)));
        copy.animated = animates;
        copy.rigid = true;
        if (play.random_phase) copy.phase_s = spawn.uniform(0.0, longest);
        for (uint32_t j = 0; j < sm.objectsPerCopy(); ++j) {
            addObject(
                scene, sm.object_mesh[j], ObjectPose{},
                (j < sm.object_names.size() ? sm.object_names[j] : "object " + std::to_string(j)) +
                    " (mover " + std::to_string(m) + " copy " + std::to_string(i) + ")",
                j < sm.object_occluder.size() ? sm.object_occluder[j] : OccluderRole::BySize,
                j < sm.object_occluder_mesh.size() ? sm.object_occluder_mesh[j]
                                                   : kNoAuthoredOccluder);
        }
        out.objects.push_back(copy.first_object);
        out.copy.push_back(static_cast<int32_t>(scene.initial_copies.size()));
        scene.initial_copies.push_back(copy);
    }
    flags.grow(scene.objectCount(), 1);
}

// A spawning mover's new objects of a built-in shape.
std::vector<uint32_t> spawnShapes(Scene& scene, const Scenario& scenario, size_t m,
                                  const WorldBox& region, MotionFlags& flags) {
    const MoverSpec& spec = scenario.movers[m];
    Rng spawn(deriveSeed(scenario.seed, m, kSpawn));
    const uint32_t mesh = addMesh(scene, spawnMesh(spec.spawn.shape));
    std::vector<uint32_t> objects;
    for (uint32_t i = 0; i < spec.spawn.count; ++i) {
        ObjectPose pose;
        pose.position = randomPointIn(region, spawn);
        pose.linear = glm::mat3(
            static_cast<float>(spawn.uniform(spec.spawn.size_min_m, spec.spawn.size_max_m)));
        objects.push_back(
            addObject(scene, mesh, pose,
                      "spawned " + std::to_string(i) + " (mover " + std::to_string(m) + ")",
                      OccluderRole::BySize));
    }
    flags.grow(scene.objectCount(), 0);
    return objects;
}

// A mover's listed objects of its source, each free to move.
std::vector<uint32_t> listedObjects(const Scenario& scenario, size_t m, const SourceRange& range,
                                    const MotionFlags& flags) {
    const MoverSpec& spec = scenario.movers[m];
    std::vector<uint32_t> objects;
    for (size_t i = 0; i < spec.objects.size(); ++i) {
        checkMoverObjectIndex(scenario, m, i, range.count);
        const uint32_t local = spec.objects[i];
        if (flags.animated[range.first + local]) {
            moverError(scenario, m, "objects/" + std::to_string(i),
                       "object " + std::to_string(local) +
                           " is moved by its glTF animation; a mover can move its whole "
                           "copy (\"whole_copies\": true)");
        }
        if (flags.moving[range.first + local]) {
            moverError(scenario, m, "objects/" + std::to_string(i),
                       "object " + std::to_string(local) + " already has a motion");
        }
        objects.push_back(range.first + local);
    }
    return objects;
}

// The objects a mover moves: picked from the source, listed, or spawned; or whole copies of a
// model.
MoverObjects selectMoverObjects(Scene& scene, const Scenario& scenario, size_t m,
                                std::vector<SourceRange>& ranges, const WorldBox& region, Rng& pick,
                                MotionFlags& flags, std::vector<uint8_t>& rigid_copy) {
    const MoverSpec& spec = scenario.movers[m];
    SourceRange& range = ranges.at(spec.source);
    MoverObjects out;
    if (spec.whole_copies) {
        pickWholeCopies(scene, scenario, m, range, pick, flags.moving, flags.own_mover, rigid_copy,
                        out.objects, out.copy);
    } else if (spec.spawn.model_source >= 0 && spec.selection == MoverSelection::Spawn) {
        spawnModelCopies(scene, scenario, m,
                         ranges.at(static_cast<size_t>(spec.spawn.model_source)), region, out,
                         flags);
    } else if (spec.selection == MoverSelection::Fraction) {
        out.objects = pickFraction(range, spec.fraction, pick, flags.moving);
    } else if (spec.selection == MoverSelection::Objects) {
        out.objects = listedObjects(scenario, m, range, flags);
    } else {
        out.objects = spawnShapes(scene, scenario, m, region, flags);
    }
    out.copy.resize(out.objects.size(), -1);
    return out;
}

// One object's (or copy's) motion under a mover; a path motion also places `pose` on its path.
Motion moverMotion(const MoverSpec& spec, const Scene& scene, ObjectPose& pose,
                   const WorldBox& region, const std::vector<uint32_t>& paths, Rng& pick,
                   Rng& motion) {
    const double speed = motion.uniform(spec.speed_min_mps, spec.speed_max_mps);
    switch (spec.motion) {
        case MotionType::Bounce: {
            // Mostly horizontal, like traffic; a little vertical drift where the box allows.
            const double a = motion.uniform(0.0, 2.0 * std::numbers::pi);
            const glm::dvec3 dir(std::cos(a), motion.uniform(-0.2, 0.2), std::sin(a));
            return BounceMotion{speed * glm::normalize(dir), region};
        }
        case MotionType::Orbit: {
            const double radius = motion.uniform(spec.radius_min_m, spec.radius_max_m);
            const double angle = motion.uniform(0.0, 2.0 * std::numbers::pi);
            const double sign = motion.uniform() < 0.5 ? -1.0 : 1.0;
            // Centre chosen so that the orbit passes through the object's start position.
            const glm::dvec3 center =
                pose.position - radius * glm::dvec3(std::cos(angle), 0, std::sin(angle));
            return OrbitMotion{center, radius, sign * speed / radius, angle};
        }
        case MotionType::Path: {
            const uint32_t path = paths[pick.below(static_cast<uint32_t>(paths.size()))];
            const MotionPath& p = scene.paths[path];
            const double distance = spec.selection == MoverSelection::Spawn
                                        ? motion.uniform(0.0, p.total())
                                        : nearestDistanceOnPath(p, pose.position);
            glm::dvec3 direction;
            pose.position = pointOnPath(p, distance, &direction);
            pose.rotation = yawTowards(direction);
            return PathMotion{path, distance, speed};
        }
        case MotionType::RandomWalk: {
            RandomWalkMotion walk;
            walk.speed_mps = speed;
            walk.heading = motion.uniform(0.0, 2.0 * std::numbers::pi);
            walk.turn_rate = glm::radians(spec.turn_rate_deg_s);
            walk.region = region;
            walk.rng = Rng(motion.next());
            return walk;
        }
        case MotionType::Spin: {
            const double rate =
                glm::radians(motion.uniform(spec.spin_min_deg_s, spec.spin_max_deg_s));
            return SpinMotion{motion.uniform() < 0.5 ? -rate : rate, 0.0, pose.rotation};
        }
    }
    return BounceMotion{};
}

// One mover of the scenario: its objects chosen or spawned, each given its motion.
void placeMover(Scene& scene, const Scenario& scenario, size_t m, std::vector<SourceRange>& ranges,
                MotionFlags& flags, std::vector<uint8_t>& rigid_copy) {
    const MoverSpec& spec = scenario.movers[m];
    Rng pick(deriveSeed(scenario.seed, m, kMoverPick));
    Rng motion(deriveSeed(scenario.seed, m, kMoverMotion));
    const WorldBox region = spec.has_region ? spec.region : ranges.at(spec.source).region;
    const std::vector<uint32_t> paths = moverPaths(scene, scenario, m, ranges.at(spec.source));
    const MoverObjects chosen =
        selectMoverObjects(scene, scenario, m, ranges, region, pick, flags, rigid_copy);
    for (size_t i = 0; i < chosen.objects.size(); ++i) {
        const uint32_t object = chosen.objects[i];
        const int32_t copy = chosen.copy[i];
        flags.moving[object] = 1;
        if (copy < 0) flags.own_mover[object] = 1;
        ObjectPose& pose = copy >= 0 ? scene.initial_copies[static_cast<size_t>(copy)].anchor
                                     : scene.initial_poses[object];
        const Motion m_motion = moverMotion(spec, scene, pose, region, paths, pick, motion);
        scene.initial_movers.push_back(Mover{object, m_motion, copy});
    }
}

}  // namespace

Scene buildScene(const Scenario& scenario) {
    Scene scene;
    scene.lights = scenario.lights;  // the scenario's first, then each placed glTF file's
    std::vector<SourceRange> ranges = addSources(scene, scenario);
    MotionFlags flags = animatedObjects(scene);
    std::vector<uint8_t> rigid_copy;  // per initial copy: a mover moves it whole
    for (size_t m = 0; m < scenario.movers.size(); ++m) {
        placeMover(scene, scenario, m, ranges, flags, rigid_copy);
    }
    if (scene.objectCount() == 0) {
        throw ScenarioError(scenario.file.string(), "/scene/sources",
                            "nothing is placed: the glTF sources have \"place\": false and no "
                            "mover spawns their models");
    }
    // Moving copies start in their pose at time 0 (animations and anchors as the movers placed
    // them).
    ModelPoseBuffers buffers = makePoseBuffers(scene.models);
    poseCopies(scene, 0.0, scene.initial_copies, buffers, scene.initial_poses, nullptr);
    scene.culling_origin = cullingOriginOf(scenario.camera);
    return scene;
}

}  // namespace occsim
