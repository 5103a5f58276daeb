// Small glTF documents built in tests: JSON with one embedded base64 buffer, and temporary
// folders to write them (and scenarios using them) to.
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace occsim::testing_gltf {

using nlohmann::json;

constexpr int kPoints = 0, kLines = 1, kTriangles = 4, kStrip = 5, kFan = 6;
constexpr int kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;

// ---- Temporary files -----------------------------------------------------------------------

class TempDir {
  public:
    TempDir() {
        static int counter = 0;
        path_ =
            std::filesystem::temp_directory_path() /
            ("occsim-test-gltf-" + std::to_string(::getpid()) + "-" + std::to_string(++counter));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path write(const std::string& name, const std::string& bytes) const {
        const std::filesystem::path file = path_ / name;
        std::ofstream(file, std::ios::binary)
            .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        return file;
    }

  private:
    std::filesystem::path path_;
};

inline std::string base64(const std::vector<uint8_t>& bytes) {
    static const char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = static_cast<uint32_t>(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= static_cast<uint32_t>(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= bytes[i + 2];
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
    }
    return out;
}

// A small glTF document with one embedded buffer. Accessors are appended to the buffer, each in
// its own bufferView; meshes, nodes and the scene are plain JSON the test fills in.
class GltfBuilder {
  public:
    GltfBuilder() {
        doc_ = {{"asset", {{"version", "2.0"}}},
                {"accessors", json::array()},
                {"bufferViews", json::array()},
                {"meshes", json::array()},
                {"nodes", json::array()},
                {"scenes", json::array({{{"nodes", json::array()}}})},
                {"scene", 0}};
    }

    json& doc() { return doc_; }
    const std::vector<uint8_t>& bytes() const { return bytes_; }

    // A VEC3 FLOAT accessor; `stride` > 12 interleaves each vec3 with padding bytes.
    int vec3(const std::vector<glm::vec3>& values, size_t stride = 0) {
        const size_t step = stride == 0 ? 12 : stride;
        std::vector<uint8_t> bytes(values.empty() ? 0 : (values.size() - 1) * step + 12, 0xEE);
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (size_t i = 0; i < values.size(); ++i) {
            std::memcpy(bytes.data() + i * step, &values[i], 12);
            lo = glm::min(lo, values[i]);
            hi = glm::max(hi, values[i]);
        }
        json accessor = {{"bufferView", addView(bytes, stride)},
                         {"componentType", kFloat},
                         {"count", values.size()},
                         {"type", "VEC3"}};
        if (!values.empty()) {
            accessor["min"] = {lo.x, lo.y, lo.z};
            accessor["max"] = {hi.x, hi.y, hi.z};
        }
        return addAccessor(accessor);
    }

    // A FLOAT accessor of `type` ("SCALAR", "VEC3", "VEC4") from its components in order:
    // animation key times and values.
    int floats(const std::vector<float>& components, const std::string& type) {
        const size_t per = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 4;
        std::vector<uint8_t> bytes(components.size() * 4);
        if (!components.empty()) std::memcpy(bytes.data(), components.data(), bytes.size());
        json accessor = {{"bufferView", addView(bytes, 0)},
                         {"componentType", kFloat},
                         {"count", components.size() / per},
                         {"type", type}};
        if (type == "SCALAR" && !components.empty()) {
            accessor["min"] = {components.front()};
            accessor["max"] = {components.back()};
        }
        return addAccessor(accessor);
    }

    // An animation with one sampler per channel: {node, path, interpolation, times, values}.
    struct Track {
        int node;
        std::string path;
        std::string interpolation;
        std::vector<float> times;
        std::vector<float> values;  // components, key after key (3 per key with CUBICSPLINE)
        std::string type = "";      // default: VEC4 for rotation, else VEC3
    };
    int animation(const std::string& name, const std::vector<Track>& tracks) {
        json samplers = json::array(), channels = json::array();
        for (const Track& t : tracks) {
            const std::string type = !t.type.empty()        ? t.type
                                     : t.path == "rotation" ? "VEC4"
                                                            : "VEC3";
            samplers.push_back({{"input", floats(t.times, "SCALAR")},
                                {"output", floats(t.values, type)},
                                {"interpolation", t.interpolation}});
            json target = {{"path", t.path}};
            if (t.node >= 0) target["node"] = t.node;
            channels.push_back({{"sampler", samplers.size() - 1}, {"target", target}});
        }
        json& animations = doc_["animations"];
        if (animations.is_null()) animations = json::array();
        json a = {{"samplers", samplers}, {"channels", channels}};
        if (!name.empty()) a["name"] = name;
        animations.push_back(a);
        return static_cast<int>(animations.size() - 1);
    }

    int indices(const std::vector<uint32_t>& values, int component_type = kUnsignedInt) {
        const size_t size = component_type == kUnsignedByte    ? 1
                            : component_type == kUnsignedShort ? 2
                                                               : 4;
        std::vector<uint8_t> bytes(values.size() * size);
        for (size_t i = 0; i < values.size(); ++i) {
            const uint32_t v = values[i];
            std::memcpy(bytes.data() + i * size, &v, size);  // little-endian: the low bytes
        }
        return addAccessor({{"bufferView", addView(bytes, 0)},
                            {"componentType", component_type},
                            {"count", values.size()},
                            {"type", "SCALAR"}});
    }

    int addAccessor(const json& accessor) {
        doc_["accessors"].push_back(accessor);
        return static_cast<int>(doc_["accessors"].size() - 1);
    }

    static json primitive(int positions, int index_accessor = -1, int mode = kTriangles) {
        json p = {{"attributes", {{"POSITION", positions}}}, {"mode", mode}};
        if (index_accessor >= 0) p["indices"] = index_accessor;
        return p;
    }

    int mesh(const std::string& name, const json& primitives) {
        doc_["meshes"].push_back({{"name", name}, {"primitives", primitives}});
        return static_cast<int>(doc_["meshes"].size() - 1);
    }

    // A node; a root of scene 0 unless it is made someone's child.
    int node(const json& node, bool root = true) {
        doc_["nodes"].push_back(node);
        const int index = static_cast<int>(doc_["nodes"].size() - 1);
        if (root) doc_["scenes"][0]["nodes"].push_back(index);
        return index;
    }

    // One counter-clockwise (seen from +z) triangle in the xy plane as an indexed mesh.
    int triangleMesh(const std::string& name) {
        const int p = vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        return mesh(name, json::array({primitive(p, indices({0, 1, 2}))}));
    }

    std::string text() const {
        json doc = doc_;
        doc["buffers"] =
            json::array({{{"byteLength", bytes_.size()},
                          {"uri", "data:application/octet-stream;base64," + base64(bytes_)}}});
        return doc.dump();
    }

  private:
    int addView(std::vector<uint8_t> bytes, size_t stride) {
        while (bytes_.size() % 4 != 0) bytes_.push_back(0);  // accessors must be aligned
        json view = {{"buffer", 0}, {"byteOffset", bytes_.size()}, {"byteLength", bytes.size()}};
        if (stride != 0) view["byteStride"] = stride;
        bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
        doc_["bufferViews"].push_back(view);
        return static_cast<int>(doc_["bufferViews"].size() - 1);
    }

    json doc_;
    std::vector<uint8_t> bytes_;
};

}  // namespace occsim::testing_gltf
