// The scenario parser: JSON (format_version 1, docs/scenario-format.md) -> Scenario.
//
// Each section has its own small function that reads every key it allows, validates ranges that
// depend on other keys (near < far, warmup < frames, ...) and calls finish() so that unknown keys
// are errors. Validation that the culling module already owns (BspBuildOptions,
// StatisticalOptions) is delegated to its isValid() so there is one definition of "valid".
#include "sim/scenario.h"

#include "sim/json_reader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

namespace occsim {

namespace {

constexpr uint64_t kFormatVersion = 1;
constexpr uint64_t kMaxFrames = 10'000'000;
constexpr double kMaxDt = 10.0;
constexpr uint64_t kMinViewport = 16;
constexpr uint64_t kMaxViewport = 8192;
constexpr uint64_t kMaxTeapots = 1'000'000;
constexpr uint64_t kMaxTessellation = 64;
constexpr uint64_t kMaxUint32 = std::numeric_limits<uint32_t>::max();
constexpr uint32_t kDefaultWarmupFrames = 10;

const std::vector<std::string> kSourceTypes = {"teapots"};
const std::vector<std::string> kMotionTypes = {"bounce", "orbit"};
const std::vector<std::string> kSplitRules = {"median", "sah"};

// Read first, before any other key, so that a file written for a newer format fails with
// "wrong version" rather than with a confusing complaint about keys this version lacks.
void readFormatVersion(JsonObjectReader& top) {
    const JsonValueReader version = top.required("format_version");
    if (version.json().is_number() && version.json() == kFormatVersion) return;
    version.failExpected(std::to_string(kFormatVersion) +
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

Aabb readRegion(const JsonValueReader& value) {
    JsonObjectReader region = value.asObject();
    const JsonValueReader min_at = region.required("min");
    const JsonValueReader max_at = region.required("max");
    const Aabb box{toFloatPoint(min_at, min_at.asVec3()), toFloatPoint(max_at, max_at.asVec3())};
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

void readRunSettings(JsonObjectReader& top, Scenario& s) {
    s.seed = top.unsignedInteger("seed", s.seed);
    s.frames = static_cast<uint32_t>(top.unsignedInteger("frames", s.frames, 1, kMaxFrames));
    s.dt_s = top.number("dt", s.dt_s, NumberRange::openClosed(0.0, kMaxDt));
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

CameraSpec readCamera(JsonObjectReader camera) {
    CameraSpec spec;
    spec.fov_y_deg = camera.number("fov_y", spec.fov_y_deg, NumberRange::open(0.0, 180.0));
    spec.near_m = camera.number("near", spec.near_m, NumberRange::greaterThan(0.0));
    spec.far_m = camera.number("far", spec.far_m, NumberRange::greaterThan(0.0));
    if (!(spec.far_m > spec.near_m)) {
        // Blame the key the author wrote; when both were written, far is the one to look at.
        const bool far_given = camera.has("far");
        const std::string message = "expected far > near, got near = " +
                                    formatNumber(spec.near_m) + " and far = " +
                                    formatNumber(spec.far_m);
        camera.fail(far_given ? "far" : "near", message);
    }
    spec.loop = camera.boolean("loop", spec.loop);
    spec.keyframes = readKeyframes(camera.array("keyframes"));
    camera.finish();
    return spec;
}

TeapotFieldSpec readTeapots(JsonObjectReader& source) {
    TeapotFieldSpec spec;
    spec.count = static_cast<uint32_t>(source.unsignedInteger("count", spec.count, 1, kMaxTeapots));
    if (const auto region = source.optional("region")) spec.region = readRegion(*region);
    const auto size = source.range("size", {spec.size_min_m, spec.size_max_m},
                                   NumberRange::greaterThan(0.0));
    spec.size_min_m = size.first;
    spec.size_max_m = size.second;
    spec.tessellation = static_cast<uint32_t>(
        source.unsignedInteger("tessellation", spec.tessellation, 1, kMaxTessellation));
    return spec;
}

SceneSourceSpec readSource(const JsonValueReader& value) {
    JsonObjectReader source = value.asObject();
    SceneSourceSpec spec;
    spec.type = source.requiredEnumeration("type", kSourceTypes);
    spec.teapots = readTeapots(source);  // the only type so far
    source.finish();
    return spec;
}

std::vector<SceneSourceSpec> readScene(JsonObjectReader scene) {
    const JsonArrayReader array = scene.array("sources");
    array.requireAtLeast(1, "source");
    std::vector<SceneSourceSpec> sources;
    for (std::size_t i = 0; i < array.size(); ++i) sources.push_back(readSource(array.at(i)));
    scene.finish();
    return sources;
}

// The keys that belong to the other motion type are errors, not ignored: a "radius" on a
// bouncing mover means the author expected an orbit.
void rejectOtherMotionKey(JsonObjectReader& mover, const char* key, const char* motion,
                          const char* owner) {
    if (!mover.has(key)) return;
    mover.fail(key, std::string("'") + key + "' is not allowed with motion \"" + motion +
                        "\"; it applies to motion \"" + owner + "\" only");
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
    spec.fraction = mover.number("fraction", spec.fraction, NumberRange::closed(0.0, 1.0));
    const bool orbit = mover.requiredEnumeration("motion", kMotionTypes) == "orbit";
    spec.motion = orbit ? MotionType::Orbit : MotionType::Bounce;
    const auto speed = mover.range("speed", {spec.speed_min_mps, spec.speed_max_mps},
                                   NumberRange::atLeast(0.0));
    spec.speed_min_mps = speed.first;
    spec.speed_max_mps = speed.second;
    if (orbit) {
        rejectOtherMotionKey(mover, "region", "orbit", "bounce");
        const auto radius = mover.range("radius", {spec.radius_min_m, spec.radius_max_m},
                                        NumberRange::greaterThan(0.0));
        spec.radius_min_m = radius.first;
        spec.radius_max_m = radius.second;
    } else {
        rejectOtherMotionKey(mover, "radius", "bounce", "orbit");
        if (const auto region = mover.optional("region")) {
            spec.region = readRegion(*region);
            spec.has_region = true;
        }
    }
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

StatisticalOptions readStatistical(JsonObjectReader reader) {
    StatisticalOptions o;
    o.base_time_s = reader.number("base_time", o.base_time_s);
    o.decay_a = reader.number("decay_a", o.decay_a);
    o.decay_b = reader.number("decay_b", o.decay_b);
    o.history_length =
        static_cast<uint32_t>(reader.unsignedInteger("history_length", o.history_length, 0,
                                                     kMaxUint32));
    o.max_statistics_age_s = reader.number("max_statistics_age", o.max_statistics_age_s);
    o.queries_before_restart = static_cast<uint32_t>(
        reader.unsignedInteger("queries_before_restart", o.queries_before_restart, 0, kMaxUint32));
    reader.finish();
    std::string why;
    if (!o.isValid(&why)) reader.failHere(why);
    return o;
}

void readCulling(JsonObjectReader& top, Scenario& s) {
    auto culling = top.optionalObject("culling");
    if (!culling) return;
    s.algorithm = culling->enumeration("algorithm", cullerNames(), s.algorithm);
    if (auto statistical = culling->optionalObject("statistical")) {
        s.culler.statistical = readStatistical(std::move(*statistical));
    }
    culling->finish();
}

BspBuildOptions readBsp(JsonObjectReader& top) {
    BspBuildOptions o;
    auto bsp = top.optionalObject("bsp");
    if (!bsp) return o;
    const bool sah = bsp->enumeration("split", kSplitRules, "median") == "sah";
    o.split_rule = sah ? BspSplitRule::Sah : BspSplitRule::Median;
    o.max_depth = static_cast<uint32_t>(bsp->unsignedInteger("max_depth", o.max_depth, 0,
                                                             kMaxUint32));
    o.max_objects_per_leaf = static_cast<uint32_t>(
        bsp->unsignedInteger("max_objects_per_leaf", o.max_objects_per_leaf, 0, kMaxUint32));
    o.root_margin = static_cast<float>(bsp->number("root_margin", o.root_margin));
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

nlohmann::json readExpect(JsonObjectReader& top) {
    const auto value = top.optional("expect");
    if (!value) return nullptr;
    if (!value->json().is_object()) value->failExpected("an object");
    return value->json();
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
    s.sources = readScene(top.object("scene"));
    s.movers = readMovers(top, s.sources.size());
    readCulling(top, s);
    s.bsp = readBsp(top);
    s.expect = readExpect(top);
    top.finish();
    return s;
}

Scenario parseScenarioFile(const std::filesystem::path& file) {
    return parseScenarioText(readFile(file), file);
}

}  // namespace occsim
