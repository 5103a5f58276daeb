#include "sim/view/recorded_scenario.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "sim/output/atomic_file.h"

namespace occsim {
namespace {

// Key order as the author wrote it (nlohmann::json would sort the keys).
using OrderedJson = nlohmann::ordered_json;

// Relative to the new folder when the two share more than the file-system root (a scenario and
// its assets that move together keep working), absolute otherwise. Canonical paths, because the
// system resolves ".." after following symbolic links, not textually.
std::string relocated(const std::filesystem::path& resolved, const std::filesystem::path& new_dir) {
    const std::filesystem::path target =
        std::filesystem::weakly_canonical(std::filesystem::absolute(resolved));
    const std::filesystem::path base =
        std::filesystem::weakly_canonical(std::filesystem::absolute(new_dir));
    auto t = target.begin(), b = base.begin();
    size_t shared = 0;
    for (; t != target.end() && b != base.end() && *t == *b; ++t, ++b) ++shared;
    if (shared <= 1) return target.generic_string();  // only the root in common
    return target.lexically_relative(base).generic_string();
}

OrderedJson vec3Json(const glm::dvec3& v) { return OrderedJson::array({v.x, v.y, v.z}); }

// Scenario files are written by hand: short objects and arrays of numbers on one line, as the
// authors write them (nlohmann's indented dump puts every number on its own line).
bool isFlat(const OrderedJson& value) {
    if (value.is_array()) {
        return std::all_of(value.begin(), value.end(),
                           [](const OrderedJson& v) { return v.is_primitive(); });
    }
    if (value.is_object()) {
        return std::all_of(value.begin(), value.end(), [](const OrderedJson& v) {
            return v.is_primitive() || (v.is_array() && isFlat(v));
        });
    }
    return true;
}

std::string inlineText(const OrderedJson& value) {
    if (value.is_array()) {
        std::string out = "[";
        for (size_t i = 0; i < value.size(); ++i) out += (i ? ", " : "") + inlineText(value[i]);
        return out + "]";
    }
    if (value.is_object()) {
        std::string out = "{";
        bool first = true;
        for (auto it = value.begin(); it != value.end(); ++it) {
            out +=
                (first ? "" : ", ") + OrderedJson(it.key()).dump() + ": " + inlineText(it.value());
            first = false;
        }
        return out + "}";
    }
    return value.dump();
}

constexpr size_t kMaxLine = 110;

// `in_array`: an element of an array, which gets a line of its own however long (keyframes).
void writeJson(const OrderedJson& value, const std::string& indent, std::string& out,
               bool in_array = false) {
    const std::string flat = isFlat(value) ? inlineText(value) : std::string();
    if (!flat.empty() && (in_array || indent.size() + flat.size() <= kMaxLine)) {
        out += flat;
        return;
    }
    const std::string inner = indent + "  ";
    const bool array = value.is_array();
    out += array ? "[\n" : "{\n";
    size_t i = 0;
    for (auto it = value.begin(); it != value.end(); ++it, ++i) {
        out += inner;
        if (!array) out += OrderedJson(it.key()).dump() + ": ";
        writeJson(it.value(), inner, out, array);
        out += i + 1 < value.size() ? ",\n" : "\n";
    }
    out += indent + (array ? "]" : "}");
}

void clampCount(OrderedJson& object, const char* key, uint64_t max) {
    if (object.contains(key) && object[key].is_number() &&
        object[key].get<double>() > double(max)) {
        object[key] = max;
    }
}

}  // namespace

std::string recordedScenarioText(const std::string& original_text, const Scenario& original,
                                 std::span<const CameraKeyframe> keyframes,
                                 const std::filesystem::path& new_file) {
    if (keyframes.empty()) throw std::invalid_argument("a recorded scenario needs keyframes");
    // The text was parsed strictly already (no duplicate keys), so the plain parser reads it alike.
    OrderedJson doc = OrderedJson::parse(original_text);
    const uint64_t frames = keyframes.size();

    if (doc.contains("name")) doc["name"] = new_file.stem().string();
    doc["frames"] = frames;
    clampCount(doc, "warmup_frames", frames - 1);

    OrderedJson camera = OrderedJson::object();
    for (const char* lens : {"fov_y", "near", "far"}) {
        if (doc["camera"].contains(lens)) camera[lens] = doc["camera"][lens];
    }
    OrderedJson& keys = camera["keyframes"] = OrderedJson::array();
    for (const CameraKeyframe& k : keyframes) {
        keys.push_back({{"time", k.time_s},
                        {"position", vec3Json(k.position)},
                        {"target", vec3Json(k.target)}});
    }
    doc["camera"] = camera;

    OrderedJson& sources = doc["scene"]["sources"];
    for (size_t i = 0; i < original.sources.size() && i < sources.size(); ++i) {
        if (const auto* gltf = std::get_if<GltfSourceSpec>(&original.sources[i].spec)) {
            sources[i]["path"] = relocated(gltf->path, new_file.parent_path());
        }
    }

    if (doc.contains("expect")) {
        doc["expect"].erase("baseline");
        clampCount(doc["expect"], "frames", frames);
    }

    std::string text;
    writeJson(doc, "", text);
    text += "\n";
    parseScenarioText(text, new_file);  // never write a scenario that run would refuse
    return text;
}

void writeRecordedScenario(const std::string& original_text, const Scenario& original,
                           std::span<const CameraKeyframe> keyframes,
                           const std::filesystem::path& new_file) {
    // The folder first: checking the text resolves its relative paths from there.
    if (new_file.has_parent_path()) std::filesystem::create_directories(new_file.parent_path());
    writeFileAtomically(new_file,
                        recordedScenarioText(original_text, original, keyframes, new_file));
}

}  // namespace occsim
