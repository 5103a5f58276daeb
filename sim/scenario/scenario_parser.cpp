// The scenario parser: JSON (format_version 1, docs/scenario-format.md) -> Scenario.
//
// Each section has its own small function that reads every key it allows, validates ranges that
// depend on other keys (near < far, warmup < frames, ...) and calls finish() so that unknown keys
// are errors. Validation that the culling module already owns (BspBuildOptions,
// StatisticalOptions) is delegated to its isValid() so there is one definition of "valid".
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

#include "occsim/culling/registry/plugin_loader.h"
#include "occsim/culling/registry/registry.h"
#include "sim/scenario/json_reader.h"
#include "sim/scenario/parser_parts.h"
#include "sim/scenario/scenario.h"

namespace occsim {

namespace {

constexpr uint64_t kScenarioFormatVersion = 1;
constexpr uint64_t kMaxFrames = 10'000'000;
constexpr double kMaxDt = 10.0;
// About 3,000 years: a double still resolves well under a microsecond there.
constexpr double kMaxStartTime = 1e11;
constexpr uint64_t kMinViewport = 16;
constexpr uint64_t kMaxViewport = 8192;
constexpr uint32_t kDefaultWarmupFrames = 10;

const std::vector<std::string> kSourceTypes = {"teapots", "gltf", "city", "library", "plant"};
const std::vector<std::string> kMotionTypes = {"bounce", "orbit", "path", "random_walk", "spin"};
const std::vector<std::string> kSpawnShapes = {"teapot", "box", "sphere"};
constexpr uint64_t kMaxSpawn = 1'000'000;
constexpr uint32_t kOrbitKeyframesPerTurn = 16;
const std::vector<std::string> kSplitRules = {"median", "sah"};
const std::vector<std::string> kDepthModes = {"reverse_float", "conventional_24"};

// Read first, before any other key, so that a file written for a newer format fails with
// "wrong version" rather than with a confusing complaint about keys this version lacks.
void readFormatVersion(JsonObjectReader& top) {
    const JsonValueReader version = top.required("format_version");
    if (version.json().is_number() && version.json() == kScenarioFormatVersion) return;
    version.failExpected(std::to_string(kScenarioFormatVersion) +
                         " (the only format_version this program reads)");
}

// Region boxes are stored as float (Aabb); a coordinate that is finite as a double can still
// overflow a float, which would silently make the box infinite.
glm::vec3 toFloatPoint(const JsonValueReader& at, const glm::dvec3& p) {
    const glm::vec3 result(p);
    if (!std::isfinite(result.x) || !std::isfinite(result.y) || !std::isfinite(result.z)) {
        at.fail("coordinates must fit in a 32-bit float (|x| < 3.4e38)");
    }
    return result;
}

void readRunSettings(JsonObjectReader& top, Scenario& s) {
    s.seed = top.unsignedInteger("seed", s.seed);
    s.frames = static_cast<uint32_t>(top.unsignedInteger("frames", s.frames, 1, kMaxFrames));
    s.dt_s = top.number("dt", s.dt_s, NumberRange::openClosed(0.0, kMaxDt));
    s.start_time_s =
        top.number("start_time", s.start_time_s, NumberRange::closed(0.0, kMaxStartTime));
    // The default warm-up shrinks for very short runs so that `frames` alone is always valid.
    const uint32_t default_warmup = std::min(kDefaultWarmupFrames, s.frames - 1);
    s.warmup_frames =
        static_cast<uint32_t>(top.unsignedInteger("warmup_frames", default_warmup, 0, kMaxUint32));
    if (s.warmup_frames >= s.frames) {
        top.required("warmup_frames")
            .failExpected("an integer < frames (" + std::to_string(s.frames) + ")");
    }
}

void readViewport(JsonObjectReader& top, Scenario& s) {
    auto viewport = top.optionalObject("viewport");
    if (!viewport) return;
    s.width = static_cast<uint32_t>(
        viewport->unsignedInteger("width", s.width, kMinViewport, kMaxViewport));
    s.height = static_cast<uint32_t>(
        viewport->unsignedInteger("height", s.height, kMinViewport, kMaxViewport));
    s.conventional_depth =
        viewport->enumeration("depth", kDepthModes, "reverse_float") == "conventional_24";
    viewport->finish();
}

CameraKeyframe readKeyframe(const JsonValueReader& value, const CameraKeyframe* previous) {
    JsonObjectReader reader = value.asObject();
    CameraKeyframe key;
    const JsonValueReader time = reader.required("time");
    key.time_s = time.asNumber(NumberRange::atLeast(0.0));
    if (previous != nullptr && !(key.time_s > previous->time_s)) {
        time.failExpected("a time > " + formatNumber(previous->time_s) +
                          " (keyframe times must strictly increase)");
    }
    key.position = reader.requiredVec3("position");
    key.target = reader.requiredVec3("target");
    if (key.position == key.target) {
        reader.fail("target", "target must differ from position (the camera needs a direction)");
    }
    reader.finish();
    return key;
}

std::vector<CameraKeyframe> readKeyframes(const JsonArrayReader& array) {
    array.requireAtLeast(1, "keyframe");
    std::vector<CameraKeyframe> keys;
    keys.reserve(array.size());
    for (std::size_t i = 0; i < array.size(); ++i) {
        keys.push_back(readKeyframe(array.at(i), keys.empty() ? nullptr : &keys.back()));
    }
    return keys;
}

// "orbit": a closed circle around `center` (16 keyframes per turn, looped), looking at `target`.
std::vector<CameraKeyframe> orbitKeyframes(JsonObjectReader orbit, CameraSpec& spec) {
    const glm::dvec3 center = orbit.requiredVec3("center");
    const double radius = orbit.requiredNumber("radius", NumberRange::greaterThan(0.0));
    const double height = orbit.number("height", 0.0);
    const double period = orbit.requiredNumber("period", NumberRange::greaterThan(0.0));
    const glm::dvec3 target = orbit.vec3("target", center);
    orbit.finish();
    std::vector<CameraKeyframe> keys;
    for (uint32_t i = 0; i <= kOrbitKeyframesPerTurn; ++i) {
        const double angle = 2.0 * 3.14159265358979323846 * i / kOrbitKeyframesPerTurn;
        const glm::dvec3 position =
            center + glm::dvec3(radius * std::cos(angle), height, radius * std::sin(angle));
        if (position == target) orbit.fail("target", "the orbit passes through the target");
        keys.push_back({period * i / kOrbitKeyframesPerTurn, position, target});
    }
    spec.loop = true;
    return keys;
}

// "fly": a straight flight from `from` to `to` over `duration` seconds, looking ahead.
std::vector<CameraKeyframe> flyKeyframes(JsonObjectReader fly) {
    const glm::dvec3 from = fly.requiredVec3("from");
    const glm::dvec3 to = fly.requiredVec3("to");
    const double duration = fly.requiredNumber("duration", NumberRange::greaterThan(0.0));
    const double look_ahead = fly.number("look_ahead", 50.0, NumberRange::greaterThan(0.0));
    fly.finish();
    if (from == to) fly.fail("to", "'to' must differ from 'from'");
    const glm::dvec3 direction = glm::normalize(to - from);
    return {{0.0, from, from + look_ahead * direction},
            {duration, to, to + look_ahead * direction}};
}

CameraSpec readCamera(JsonObjectReader camera) {
    CameraSpec spec;
    spec.fov_y_deg = camera.number("fov_y", spec.fov_y_deg, NumberRange::open(0.0, 180.0));
    spec.near_m = camera.number("near", spec.near_m, NumberRange::greaterThan(0.0));
    spec.far_m = camera.number("far", spec.far_m, NumberRange::greaterThan(0.0));
    if (!(spec.far_m > spec.near_m)) {
        // Blame the key the author wrote; when both were written, far is the one to look at.
        const bool far_given = camera.has("far");
        const std::string message = "expected far > near, got near = " + formatNumber(spec.near_m) +
                                    " and far = " + formatNumber(spec.far_m);
        camera.fail(far_given ? "far" : "near", message);
    }
    spec.loop = camera.boolean("loop", spec.loop);
    const int paths = camera.has("keyframes") + camera.has("orbit") + camera.has("fly");
    if (paths != 1) {
        camera.failHere("expected exactly one of 'keyframes', 'orbit' or 'fly', got " +
                        std::to_string(paths));
    }
    if (camera.has("keyframes")) {
        spec.keyframes = readKeyframes(camera.array("keyframes"));
    } else if (camera.has("orbit")) {
        spec.keyframes = orbitKeyframes(camera.object("orbit"), spec);
    } else {
        spec.keyframes = flyKeyframes(camera.object("fly"));
    }
    camera.finish();
    return spec;
}

SceneSourceSpec readSource(const JsonValueReader& value, const std::filesystem::path& dir) {
    JsonObjectReader source = value.asObject();
    SceneSourceSpec spec;
    const std::string type = source.requiredEnumeration("type", kSourceTypes);
    if (type == "teapots") {
        spec.type = SourceType::Teapots;
        spec.spec = readTeapotField(source);
    } else if (type == "gltf") {
        spec.type = SourceType::Gltf;
        spec.spec = readGltfSource(source, dir);
    } else if (type == "city") {
        spec.type = SourceType::City;
        spec.spec = readCity(source);
    } else if (type == "library") {
        spec.type = SourceType::Library;
        spec.spec = readLibrary(source);
    } else {
        spec.type = SourceType::Plant;
        spec.spec = readPlant(source);
    }
    static const std::vector<std::string> kRoles = {"by_size", "always", "never"};
    const std::string role = source.enumeration("occluders", kRoles, "by_size");
    spec.occluders = role == "always"  ? OccluderRole::Always
                     : role == "never" ? OccluderRole::Never
                                       : OccluderRole::BySize;
    source.finish();
    return spec;
}

std::vector<SceneSourceSpec> readScene(JsonObjectReader scene, const std::filesystem::path& dir) {
    const JsonArrayReader array = scene.array("sources");
    array.requireAtLeast(1, "source");
    std::vector<SceneSourceSpec> sources;
    for (std::size_t i = 0; i < array.size(); ++i) sources.push_back(readSource(array.at(i), dir));
    scene.finish();
    return sources;
}

// Keys that belong to another motion are errors, not ignored: a "radius" on a bouncing mover
// means the author expected an orbit.
struct MotionKey {
    const char* key;
    const char* motions;  // the motions it applies to, as written in the message
    bool (*applies)(MotionType);
};

const MotionKey kMotionKeys[] = {
    {"speed", "bounce, orbit, path, random_walk",
     [](MotionType m) { return m != MotionType::Spin; }},
    {"region", "bounce, random_walk",
     [](MotionType m) { return m == MotionType::Bounce || m == MotionType::RandomWalk; }},
    {"radius", "orbit", [](MotionType m) { return m == MotionType::Orbit; }},
    {"waypoints", "path", [](MotionType m) { return m == MotionType::Path; }},
    {"turn_rate", "random_walk", [](MotionType m) { return m == MotionType::RandomWalk; }},
    {"spin", "spin", [](MotionType m) { return m == MotionType::Spin; }},
};

MotionType motionFromName(const std::string& name) {
    if (name == "bounce") return MotionType::Bounce;
    if (name == "orbit") return MotionType::Orbit;
    if (name == "path") return MotionType::Path;
    if (name == "random_walk") return MotionType::RandomWalk;
    return MotionType::Spin;
}

void readSelection(JsonObjectReader& mover, MoverSpec& spec) {
    const int given = mover.has("fraction") + mover.has("objects") + mover.has("spawn");
    if (given != 1) {
        mover.failHere(
            "expected exactly one of 'fraction', 'objects' or 'spawn' (which objects "
            "move), got " +
            std::to_string(given));
    }
    if (mover.has("fraction")) {
        spec.selection = MoverSelection::Fraction;
        spec.fraction = mover.requiredNumber("fraction", NumberRange::closed(0.0, 1.0));
    } else if (mover.has("objects")) {
        spec.selection = MoverSelection::Objects;
        const JsonArrayReader objects = mover.array("objects");
        objects.requireAtLeast(1, "object index");
        for (std::size_t i = 0; i < objects.size(); ++i) {
            spec.objects.push_back(static_cast<uint32_t>(objects.at(i).asUnsigned(0, kMaxUint32)));
        }
    } else {
        spec.selection = MoverSelection::Spawn;
        JsonObjectReader spawn = mover.object("spawn");
        spec.spawn.count =
            static_cast<uint32_t>(spawn.requiredUnsignedInteger("count", 1, kMaxSpawn));
        const std::string shape = spawn.enumeration("shape", kSpawnShapes, "teapot");
        spec.spawn.shape = shape == "teapot" ? SpawnShape::Teapot
                           : shape == "box"  ? SpawnShape::Box
                                             : SpawnShape::Sphere;
        if (const auto model = spawn.optional("model")) {
            if (spawn.has("shape")) spawn.fail("model", "give either 'shape' or 'model', not both");
            // Checked against the sources (a glTF one) when the scene is built.
            spec.spawn.model_source = static_cast<int32_t>(model->asUnsigned(0, INT32_MAX));
            // A model keeps its own size unless 'size' scales it.
            spec.spawn.size_min_m = spec.spawn.size_max_m = 1.0;
        }
        const auto size = spawn.range("size", {spec.spawn.size_min_m, spec.spawn.size_max_m},
                                      NumberRange::greaterThan(0.0));
        spec.spawn.size_min_m = size.first;
        spec.spawn.size_max_m = size.second;
        spawn.finish();
    }
}

MoverSpec readMover(const JsonValueReader& value, std::size_t source_count) {
    JsonObjectReader mover = value.asObject();
    MoverSpec spec;
    const auto source = mover.optional("source");
    spec.source = source ? static_cast<uint32_t>(source->asUnsigned(0, kMaxUint32)) : 0;
    if (spec.source >= source_count) {
        const JsonValueReader at = source ? *source : value;
        at.failExpected("an index into scene.sources, which has " + std::to_string(source_count) +
                        (source_count == 1 ? " entry" : " entries"));
    }
    readSelection(mover, spec);
    spec.whole_copies = mover.boolean("whole_copies", false);
    if (spec.whole_copies && spec.selection == MoverSelection::Spawn) {
        mover.fail("whole_copies",
                   "'whole_copies' applies to 'fraction' and 'objects'; spawned "
                   "models always move whole");
    }
    spec.motion = motionFromName(mover.requiredEnumeration("motion", kMotionTypes));
    const std::string motion_name = mover.required("motion").asString();
    for (const MotionKey& k : kMotionKeys) {
        if (!k.applies(spec.motion) && mover.has(k.key)) {
            mover.fail(k.key, std::string("'") + k.key + "' is not allowed with motion \"" +
                                  motion_name + "\"; it applies to " + k.motions + " only");
        }
    }
    const auto speed =
        mover.range("speed", {spec.speed_min_mps, spec.speed_max_mps}, NumberRange::atLeast(0.0));
    spec.speed_min_mps = speed.first;
    spec.speed_max_mps = speed.second;
    if (const auto region = mover.optional("region")) {
        spec.region = readRegion(*region);
        spec.has_region = true;
    }
    const auto radius = mover.range("radius", {spec.radius_min_m, spec.radius_max_m},
                                    NumberRange::greaterThan(0.0));
    spec.radius_min_m = radius.first;
    spec.radius_max_m = radius.second;
    if (const auto waypoints = mover.optionalArray("waypoints")) {
        waypoints->requireAtLeast(2, "waypoint");
        for (std::size_t i = 0; i < waypoints->size(); ++i) {
            spec.waypoints.push_back(waypoints->at(i).asVec3());
        }
    }
    spec.turn_rate_deg_s =
        mover.number("turn_rate", spec.turn_rate_deg_s, NumberRange::atLeast(0.0));
    const auto spin =
        mover.range("spin", {spec.spin_min_deg_s, spec.spin_max_deg_s}, NumberRange::atLeast(0.0));
    spec.spin_min_deg_s = spin.first;
    spec.spin_max_deg_s = spin.second;
    mover.finish();
    return spec;
}

std::vector<MoverSpec> readMovers(JsonObjectReader& top, std::size_t source_count) {
    std::vector<MoverSpec> movers;
    const auto array = top.optionalArray("movers");
    if (!array) return movers;
    for (std::size_t i = 0; i < array->size(); ++i) {
        movers.push_back(readMover(array->at(i), source_count));
    }
    return movers;
}

BspBuildOptions readBsp(JsonObjectReader& top) {
    BspBuildOptions o;
    auto bsp = top.optionalObject("bsp");
    if (!bsp) return o;
    const bool sah = bsp->enumeration("split", kSplitRules, "median") == "sah";
    o.split_rule = sah ? BspSplitRule::Sah : BspSplitRule::Median;
    o.max_depth =
        static_cast<uint32_t>(bsp->unsignedInteger("max_depth", o.max_depth, 0, kMaxUint32));
    o.max_objects_per_leaf = static_cast<uint32_t>(
        bsp->unsignedInteger("max_objects_per_leaf", o.max_objects_per_leaf, 0, kMaxUint32));
    o.root_margin = static_cast<float>(bsp->number("root_margin", o.root_margin));
    o.looseness = static_cast<float>(bsp->number("looseness", o.looseness));
    o.adapt = bsp->boolean("adapt", o.adapt);
    o.max_root_growth = static_cast<float>(bsp->number("max_root_growth", o.max_root_growth));
    bsp->finish();
    std::string why;
    if (!o.isValid(&why)) bsp->failHere(why);
    return o;
}

std::string readName(JsonObjectReader& top, const std::filesystem::path& file) {
    const auto value = top.optional("name");
    if (!value) return file.stem().string();
    std::string name = value->asString();
    if (name.empty()) value->failExpected("a non-empty string");
    return name;
}

std::optional<Expectations> readExpect(JsonObjectReader& top, const Scenario& s) {
    const auto value = top.optional("expect");
    if (!value) return std::nullopt;
    return readExpectations(value->asObject(), s);
}

std::string readFile(const std::filesystem::path& file) {
    const std::string name = file.string();
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec)) {
        throw ScenarioError(name, "", "cannot open file: it is a directory");
    }
    struct Closer {
        void operator()(std::FILE* f) const { std::fclose(f); }
    };
    // stdio rather than ifstream: fopen sets errno, so the message can say why it failed.
    const std::unique_ptr<std::FILE, Closer> stream(std::fopen(name.c_str(), "rb"));
    if (!stream) {
        throw ScenarioError(name, "", std::string("cannot open file: ") + std::strerror(errno));
    }
    std::string text;
    char buffer[1 << 16];
    std::size_t read = 0;
    while ((read = std::fread(buffer, 1, sizeof(buffer), stream.get())) > 0) {
        text.append(buffer, read);
    }
    if (std::ferror(stream.get())) {
        throw ScenarioError(name, "", std::string("cannot read file: ") + std::strerror(errno));
    }
    return text;
}

}  // namespace

// In double, as the camera and every pose: only checked to fit in float, which object boxes use.
WorldBox readRegion(const JsonValueReader& value) {
    JsonObjectReader region = value.asObject();
    const JsonValueReader min_at = region.required("min");
    const JsonValueReader max_at = region.required("max");
    const WorldBox box{min_at.asVec3(), max_at.asVec3()};
    toFloatPoint(min_at, box.min);
    toFloatPoint(max_at, box.max);
    region.finish();
    for (int axis = 0; axis < 3; ++axis) {
        if (box.min[axis] > box.max[axis]) {
            region.failHere("expected min <= max on every axis, but min." +
                            std::string(1, "xyz"[axis]) + " = " + formatNumber(box.min[axis]) +
                            " > max." + std::string(1, "xyz"[axis]) + " = " +
                            formatNumber(box.max[axis]));
        }
    }
    return box;
}

std::optional<uint32_t> knownObjectCount(const SceneSourceSpec& source) {
    if (source.type == SourceType::Teapots) return std::get<TeapotFieldSpec>(source.spec).count;
    return std::nullopt;
}

void checkMoverObjectIndex(const Scenario& scenario, size_t mover, size_t item,
                           uint32_t source_object_count) {
    const MoverSpec& spec = scenario.movers[mover];
    const uint32_t local = spec.objects[item];
    if (local < source_object_count) return;
    throw ScenarioError(scenario.file.string(),
                        "/movers/" + std::to_string(mover) + "/objects/" + std::to_string(item),
                        "expected an object index < " + std::to_string(source_object_count) +
                            " (source " + std::to_string(spec.source) + "'s object count), got " +
                            std::to_string(local));
}

// "plugins": shared objects with cullers (occsim/culling/plugin.h), loaded before the
// culling section is read so that it may name their cullers and give their options. Paths
// resolve against the scenario's folder.
static std::vector<std::filesystem::path> readPlugins(JsonObjectReader& top,
                                                      const std::filesystem::path& scenario_dir) {
    std::vector<std::filesystem::path> plugins;
    const auto list = top.optionalArray("plugins");
    if (!list) return plugins;
    for (size_t i = 0; i < list->size(); ++i) {
        const JsonValueReader item = list->at(i);
        const std::string text = item.asString();
        if (text.empty()) item.failExpected("a path to a plugin (a shared object)");
        const std::filesystem::path path = scenario_dir / text;
        try {
            loadPlugin(path);
        } catch (const PluginError& e) {
            item.fail(e.what());
        }
        plugins.push_back(path);
    }
    return plugins;
}

Scenario parseScenarioText(const std::string& text, const std::filesystem::path& file) {
    const std::string file_name = file.string();
    const Json root = parseStrictJson(text, file_name);
    JsonObjectReader top(root, "", file_name);
    readFormatVersion(top);

    Scenario s;
    s.file = file;
    s.name = readName(top, file);
    readRunSettings(top, s);
    readViewport(top, s);
    s.camera = readCamera(top.object("camera"));
    s.lights = readLights(top);
    s.stereo = readStereo(top);
    s.sources = readScene(top.object("scene"), file.parent_path());
    s.movers = readMovers(top, s.sources.size());
    for (size_t m = 0; m < s.movers.size(); ++m) {
        const MoverSpec& mover = s.movers[m];
        const std::string at = "/movers/" + std::to_string(m);
        if (mover.whole_copies && s.sources[mover.source].type != SourceType::Gltf) {
            throw ScenarioError(file_name, at + "/whole_copies",
                                "whole copies are copies of a glTF model; source " +
                                    std::to_string(mover.source) + " is not a glTF source");
        }
        if (mover.spawn.model_source >= 0 &&
            (static_cast<size_t>(mover.spawn.model_source) >= s.sources.size() ||
             s.sources[static_cast<size_t>(mover.spawn.model_source)].type != SourceType::Gltf)) {
            throw ScenarioError(file_name, at + "/spawn/model",
                                "expected the index of a glTF source in scene.sources, got " +
                                    std::to_string(mover.spawn.model_source));
        }
        const std::optional<uint32_t> count = knownObjectCount(s.sources[s.movers[m].source]);
        if (!count) continue;
        for (size_t i = 0; i < s.movers[m].objects.size(); ++i)
            checkMoverObjectIndex(s, m, i, *count);
    }
    s.plugins = readPlugins(top, file.parent_path());
    readCulling(top, s);
    s.bsp = readBsp(top);
    s.segments = readSegments(top, s);
    s.expect = readExpect(top, s);
    top.finish();
    return s;
}

std::string readScenarioFileText(const std::filesystem::path& file) { return readFile(file); }

Scenario parseScenarioFile(const std::filesystem::path& file) {
    return parseScenarioText(readFile(file), file);
}

}  // namespace occsim
