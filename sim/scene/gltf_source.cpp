// glTF 2.0 files as a scene source (contract in sim/scene/gltf_source.h), read with tinygltf 2.7.
//
// Debian ships tinygltf as a compiled shared library (libtinygltf.so, see its README.Debian), so
// this file only includes the header and links TinyGLTF::TinyGLTF; defining
// TINYGLTF_IMPLEMENTATION here would compile a second copy of the library. Images are never
// decoded: a no-op image loader stands in for stb_image.
//
// Supported: .gltf with embedded (data: URI) or external buffers, and .glb; the default scene
// (else scene 0, else every root node); node hierarchies with `matrix` or TRS transforms;
// TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives (strips and fans become lists), indexed
// with u8/u16/u32 indices or not; FLOAT VEC3 positions and normals with any byteStride. All
// triangle primitives of a glTF mesh become one MeshData, converted once however many nodes use
// it. Normals are computed (area weighted over the triangles sharing a vertex) when a primitive
// has none or unusable ones. A mirroring node (negative determinant) gets a copy of its mesh with
// reversed winding, so front faces stay counter-clockwise.
//
// Skipped with a warning: POINTS and LINES primitives, primitives without POSITION or with
// quantized (integer) positions, sparse accessors, morph targets (base positions are used), skins
// (meshes drawn rigid in their bind pose), cameras. Node animations are read by gltf_animation.cpp
// and the model's hierarchy is kept (SourceOutput::model) so the world can pose it each frame.
// KHR_lights_punctual lights on the visited nodes are read by gltf_lights.cpp
// (SourceOutput::lights). Errors (GltfError, "<file>: <reason>"): unreadable file, tinygltf parse
// errors, references out of range, index values past the vertex count, non-finite positions or
// transforms, required extensions that would change the geometry, and no triangles at all.
#include "sim/scene/gltf_source.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>

#include "occsim/culling/geometry/random.h"
#include "sim/scene/gltf_detail.h"

namespace occsim {
namespace {

using namespace gltf_detail;

// A replicated model can multiply a big file by a big count; this keeps a typo within memory.
constexpr size_t kMaxObjects = 10'000'000;

std::vector<std::string> nonEmptyLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) {
            line.pop_back();
        }
        if (!line.empty()) lines.push_back(line);
    }
    return lines;
}

// tinygltf's messages may span several lines and quote a whole data: URI; a GltfError is one
// line of readable length.
std::string oneLine(const std::string& text) {
    constexpr size_t kMaxLength = 300;
    std::string joined;
    for (const std::string& line : nonEmptyLines(text)) {
        joined += (joined.empty() ? "" : "; ") + line;
    }
    if (joined.size() > kMaxLength) joined = joined.substr(0, kMaxLength) + "...";
    return joined;
}

// occsim draws no textures, so image bytes are neither decoded nor kept.
bool skipImage(tg::Image*, const int, std::string*, std::string*, int, int, const unsigned char*,
               int, void*) {
    return true;
}

// .glb files start with the magic "glTF"; anything else is handed to the JSON reader. Reading
// the magic also gives a clear error for a missing or unreadable file.
bool isBinaryGltf(const std::filesystem::path& path, const std::string& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) fail(file, "no such file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(file, "cannot open the file");
    char magic[4] = {};
    in.read(magic, sizeof magic);
    return in.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
}

tg::Model readModel(const std::filesystem::path& path, const std::string& file,
                    std::vector<std::string>& warnings) {
    const bool binary = isBinaryGltf(path, file);
    tg::TinyGLTF loader;
    loader.SetImageLoader(&skipImage, nullptr);
    tg::Model model;
    std::string err, warn;
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                           : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
    if (!ok) fail(file, err.empty() ? "not a valid glTF file" : oneLine(err));
    // tinygltf reports what it tolerated (an image it could not find, ...) as warnings.
    for (const std::string& line : nonEmptyLines(err + "\n" + warn)) {
        warnings.push_back(file + ": " + oneLine(line));
    }
    return model;
}

// Extensions that only change appearance (materials, textures, lights), which occsim does not
// draw. Any other required extension (compression, quantization, GPU instancing) changes the
// geometry, so a file requiring it cannot be loaded faithfully.
bool changesOnlyAppearance(const std::string& extension) {
    static const char* const kAppearance[] = {"KHR_texture_transform", "KHR_texture_basisu",
                                              "EXT_texture_webp", "KHR_lights_punctual"};
    if (extension.rfind("KHR_materials_", 0) == 0) return true;
    return std::find(std::begin(kAppearance), std::end(kAppearance), extension) !=
           std::end(kAppearance);
}

void checkRequiredExtensions(const tg::Model& model, const std::string& file) {
    for (const std::string& extension : model.extensionsRequired) {
        if (!changesOnlyAppearance(extension)) {
            fail(file, "requires the unsupported extension '" + extension + "'");
        }
    }
}

std::string meshLabel(const tg::Model& model, size_t mesh) {
    const std::string& name = model.meshes[mesh].name;
    return name.empty() ? "mesh #" + std::to_string(mesh) : "mesh '" + name + "'";
}

glm::vec3 readVec3(const AccessorView& v, size_t i) {
    float xyz[3];
    std::memcpy(xyz, v.data + i * v.stride, sizeof xyz);  // glTF data need not be aligned
    return {xyz[0], xyz[1], xyz[2]};
}

uint32_t readIndex(const AccessorView& v, size_t i) {
    const unsigned char* p = v.data + i * v.stride;
    switch (v.component_type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return *p;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t value;
            std::memcpy(&value, p, sizeof value);
            return value;
        }
        default: {
            uint32_t value;
            std::memcpy(&value, p, sizeof value);
            return value;
        }
    }
}

// ---- Primitives ----------------------------------------------------------------------------

std::string modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS:
            return "POINTS";
        case TINYGLTF_MODE_LINE:
            return "LINES";
        case TINYGLTF_MODE_LINE_LOOP:
            return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP:
            return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLES:
            return "TRIANGLES";
        case TINYGLTF_MODE_TRIANGLE_STRIP:
            return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN:
            return "TRIANGLE_FAN";
        default:
            return std::to_string(mode);
    }
}

bool isTriangleMode(int mode) {
    return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
           mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

// Corners (vertex indices in drawing order) to a counter-clockwise triangle list. Strips
// alternate their winding and fans share corner 0 (glTF 2.0, section 3.7.2.1); their degenerate
// triangles only join runs, so they are dropped.
std::vector<uint32_t> triangleList(int mode, const std::vector<uint32_t>& corners) {
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        return {corners.begin(), corners.end() - static_cast<std::ptrdiff_t>(corners.size() % 3)};
    }
    std::vector<uint32_t> out;
    for (size_t i = 0; i + 2 < corners.size(); ++i) {
        uint32_t a, b, c;
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            a = corners[i % 2 == 0 ? i : i + 1];
            b = corners[i % 2 == 0 ? i + 1 : i];
            c = corners[i + 2];
        } else {
            a = corners[i + 1];
            b = corners[i + 2];
            c = corners[0];
        }
        if (a == b || b == c || a == c) continue;
        out.insert(out.end(), {a, b, c});
    }
    return out;
}

// Area-weighted vertex normals of a triangle list; a vertex no triangle gives a direction to
// (unused, or only in degenerate triangles) points up, so every normal is unit length.
std::vector<glm::vec3> computeNormals(const std::vector<glm::vec3>& positions,
                                      const std::vector<uint32_t>& triangles) {
    std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
        const glm::dvec3 a(positions[triangles[t]]), b(positions[triangles[t + 1]]),
            c(positions[triangles[t + 2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);  // length = twice the area
        for (size_t k = 0; k < 3; ++k) sum[triangles[t + k]] += n;
    }
    std::vector<glm::vec3> normals(positions.size());
    for (size_t i = 0; i < sum.size(); ++i) {
        const double len = glm::length(sum[i]);
        normals[i] = len > 0.0 && std::isfinite(len) ? glm::vec3(sum[i] / len) : glm::vec3(0, 1, 0);
    }
    return normals;
}

// The primitive's NORMAL attribute made unit length, or nothing when it is absent or unusable
// (wrong type or count, sparse, zero or non-finite vectors): the caller computes normals then.
std::optional<std::vector<glm::vec3>> readNormals(const Context& c, const tg::Primitive& p,
                                                  size_t vertex_count, const std::string& what) {
    const auto it = p.attributes.find("NORMAL");
    if (it == p.attributes.end()) return std::nullopt;
    const ViewOrSkip normals = viewAccessor(c, it->second, "NORMAL of " + what);
    if (!normals.view || normals.view->type != TINYGLTF_TYPE_VEC3 ||
        normals.view->component_type != TINYGLTF_COMPONENT_TYPE_FLOAT ||
        normals.view->count != vertex_count) {
        return std::nullopt;
    }
    std::vector<glm::vec3> out(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i) {
        const glm::vec3 n = readVec3(*normals.view, i);
        const float len = glm::length(n);
        if (!(len > 0.0f) || !std::isfinite(len)) return std::nullopt;
        out[i] = n / len;
    }
    return out;
}

// The corners a primitive draws: its index values (checked against the vertex count), or
// 0..n-1 for a non-indexed primitive.
std::vector<uint32_t> readCorners(const Context& c, const tg::Primitive& p, size_t vertex_count,
                                  const std::string& what, std::string& skip_reason) {
    std::vector<uint32_t> corners;
    if (p.indices < 0) {
        corners.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) corners[i] = static_cast<uint32_t>(i);
        return corners;
    }
    const ViewOrSkip indices = viewAccessor(c, p.indices, "indices of " + what);
    if (!indices.view) {
        skip_reason = indices.skip_reason;
        return corners;
    }
    const AccessorView& v = *indices.view;
    const bool unsigned_type = v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                               v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                               v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    if (v.type != TINYGLTF_TYPE_SCALAR || !unsigned_type) {
        fail(c.file, "indices of " + what + " are not unsigned integer scalars");
    }
    corners.resize(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        corners[i] = readIndex(v, i);
        if (corners[i] >= vertex_count) {
            fail(c.file, "index value " + std::to_string(corners[i]) + " of " + what +
                             " is past its " + std::to_string(vertex_count) + " vertices");
        }
    }
    return corners;
}

// Appends one primitive's triangles to `mesh`, or returns why it was skipped (nothing appended).
std::optional<std::string> appendPrimitive(const Context& c, const tg::Primitive& p,
                                           const std::string& what, MeshData& mesh) {
    // tinygltf defaults an absent "mode" to TRIANGLES; -1 only appears in hand-built models.
    const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (!isTriangleMode(mode)) return "mode " + modeName(mode);
    const auto position = p.attributes.find("POSITION");
    if (position == p.attributes.end()) return "no POSITION attribute";
    const ViewOrSkip positions = viewAccessor(c, position->second, "POSITION of " + what);
    if (!positions.view) return positions.skip_reason;
    const AccessorView& pv = *positions.view;
    if (pv.type != TINYGLTF_TYPE_VEC3) fail(c.file, "POSITION of " + what + " is not VEC3");
    if (pv.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT) return "quantized (integer) positions";

    std::string skip_reason;
    const std::vector<uint32_t> corners = readCorners(c, p, pv.count, what, skip_reason);
    if (!skip_reason.empty()) return skip_reason;
    std::vector<uint32_t> triangles = triangleList(mode, corners);
    if (triangles.empty()) return "no triangles";

    std::vector<glm::vec3> points(pv.count);
    for (size_t i = 0; i < pv.count; ++i) {
        points[i] = readVec3(pv, i);
        if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) ||
            !std::isfinite(points[i].z)) {
            fail(c.file, "POSITION " + std::to_string(i) + " of " + what + " is not finite");
        }
    }
    std::vector<glm::vec3> normals =
        readNormals(c, p, pv.count, what).value_or(std::vector<glm::vec3>{});
    if (normals.empty()) normals = computeNormals(points, triangles);

    if (mesh.positions.size() + points.size() > UINT32_MAX) fail(c.file, what + " is too large");
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), points.begin(), points.end());
    mesh.normals.insert(mesh.normals.end(), normals.begin(), normals.end());
    for (uint32_t& index : triangles) index += base;
    mesh.indices.insert(mesh.indices.end(), triangles.begin(), triangles.end());
    return std::nullopt;
}

// All triangle primitives of glTF mesh `index` as one MeshData; what was left out is reported
// once per mesh (not per node that uses it).
MeshData convertMesh(const Context& c, size_t index) {
    const tg::Mesh& gltf_mesh = c.model.meshes[index];
    const std::string label = meshLabel(c.model, index);
    MeshData mesh;
    std::map<std::string, size_t> skipped;  // reason -> primitives
    size_t morphed = 0;
    for (size_t i = 0; i < gltf_mesh.primitives.size(); ++i) {
        const tg::Primitive& p = gltf_mesh.primitives[i];
        const std::string what = "primitive " + std::to_string(i) + " of " + label;
        if (const auto reason = appendPrimitive(c, p, what, mesh)) {
            ++skipped[*reason];
        } else if (!p.targets.empty()) {
            ++morphed;
        }
    }
    for (const auto& [reason, n] : skipped) {
        c.warnings.push_back(c.file + ": skipped " + plural(n, "primitive") + " with " + reason +
                             " in " + label);
    }
    if (morphed > 0) {
        c.warnings.push_back(c.file + ": used the base positions of " +
                             plural(morphed, "primitive") + " with morph targets in " + label);
    }
    return mesh;
}

// A mirrored copy: the same vertices with every triangle's winding reversed, for nodes whose
// transform has a negative determinant (which turns counter-clockwise faces clockwise).
MeshData reversedWinding(MeshData mesh) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    }
    return mesh;
}

// ---- Scene graph ---------------------------------------------------------------------------

// A node's rest transform, checked.
ModelNode restOf(const Context& c, const tg::Node& node, size_t index) {
    const std::string name = "node " + std::to_string(index);
    ModelNode rest;
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) fail(c.file, name + " has a matrix without 16 numbers");
        rest.has_matrix = true;
        for (int i = 0; i < 16; ++i)
            rest.matrix[i / 4][i % 4] = node.matrix[static_cast<size_t>(i)];
        return rest;  // glTF matrices are column-major, as glm's
    }
    if (!node.translation.empty()) {
        if (node.translation.size() != 3) {
            fail(c.file, name + " has a translation without 3 numbers");
        }
        rest.translation =
            glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) fail(c.file, name + " has a rotation without 4 numbers");
        const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        rest.rotation = glm::normalize(q);  // exporters round; a unit quaternion rotates
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3) fail(c.file, name + " has a scale without 3 numbers");
        rest.scale = glm::dvec3(node.scale[0], node.scale[1], node.scale[2]);
    }
    rest.matrix = glm::scale(
        glm::translate(glm::dmat4(1.0), rest.translation) * glm::mat4_cast(rest.rotation),
        rest.scale);
    return rest;
}

bool isFinite(const glm::dmat4& m) {
    for (int col = 0; col < 4; ++col) {
        for (int row = 0; row < 4; ++row) {
            if (!std::isfinite(m[col][row])) return false;
        }
    }
    return true;
}

// The roots of the scene to draw: the default scene, else scene 0, else every node that is no
// other node's child.
std::vector<int> sceneRoots(const Context& c) {
    const tg::Model& m = c.model;
    if (m.defaultScene >= static_cast<int>(m.scenes.size())) {
        fail(c.file, "the default scene " + std::to_string(m.defaultScene) + " does not exist");
    }
    if (!m.scenes.empty()) return m.scenes[static_cast<size_t>(std::max(m.defaultScene, 0))].nodes;
    std::vector<uint8_t> is_child(m.nodes.size(), 0);
    for (const tg::Node& node : m.nodes) {
        for (int child : node.children) {
            if (child >= 0 && static_cast<size_t>(child) < m.nodes.size()) {
                is_child[static_cast<size_t>(child)] = 1;
            }
        }
    }
    std::vector<int> roots;
    for (size_t i = 0; i < m.nodes.size(); ++i) {
        if (!is_child[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
}

struct MeshInstance {
    size_t mesh = 0;
    glm::dmat4 world{1.0};
    uint32_t visit = 0;  // index into SceneContent::visits
};

struct SceneContent {
    std::vector<MeshInstance> instances;
    std::vector<ModelNode> nodes;        // per node of the file (rest transforms of visited ones)
    std::vector<HierarchyVisit> visits;  // the hierarchy as visited, parents first
    std::vector<LightNode> lights;       // the nodes that carry a light (KHR_lights_punctual)
    size_t skinned = 0;
    size_t cameras = 0;
};

// Flattens the hierarchy under the scene roots, world = parent * local. Iterative, so a deep
// hierarchy cannot overflow the stack; a path longer than the node count must repeat a node, so
// it is reported as a cycle.
SceneContent flattenScene(const Context& c) {
    const tg::Model& m = c.model;
    struct Pending {
        int node;
        glm::dmat4 parent;
        size_t depth;
        int32_t parent_visit;
    };
    std::vector<Pending> stack;
    for (int root : sceneRoots(c)) stack.push_back({root, glm::dmat4(1.0), 0, -1});
    std::reverse(stack.begin(), stack.end());  // visit roots in file order
    SceneContent content;
    content.nodes.resize(m.nodes.size());
    size_t visits = 0;
    while (!stack.empty()) {
        const Pending at = stack.back();
        stack.pop_back();
        if (at.node < 0 || static_cast<size_t>(at.node) >= m.nodes.size()) {
            fail(c.file, "the scene refers to node " + std::to_string(at.node) +
                             ", but the file has " + plural(m.nodes.size(), "node"));
        }
        if (at.depth > m.nodes.size()) fail(c.file, "the node hierarchy has a cycle");
        if (++visits > kMaxObjects) fail(c.file, "the node hierarchy is too large");
        const auto index = static_cast<size_t>(at.node);
        const tg::Node& node = m.nodes[index];
        content.nodes[index] = restOf(c, node, index);
        const glm::dmat4 world = at.parent * content.nodes[index].matrix;
        const auto visit = static_cast<uint32_t>(content.visits.size());
        content.visits.push_back({static_cast<uint32_t>(index), at.parent_visit});
        if (!isFinite(world)) {
            fail(c.file, "node " + std::to_string(index) + " has a non-finite transform");
        }
        if (node.mesh >= 0) {
            if (static_cast<size_t>(node.mesh) >= m.meshes.size()) {
                fail(c.file, "node " + std::to_string(index) + " refers to mesh " +
                                 std::to_string(node.mesh) + ", but the file has " +
                                 std::to_string(m.meshes.size()) + " meshes");
            }
            content.instances.push_back({static_cast<size_t>(node.mesh), world, visit});
            if (node.skin >= 0) ++content.skinned;
        }
        if (node.camera >= 0) ++content.cameras;
        if (const int light = nodeLight(c, node, index); light != -1) {
            content.lights.push_back({index, light, world});
        }
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
            stack.push_back({*child, world, at.depth + 1, static_cast<int32_t>(visit)});
        }
    }
    return content;
}

void warnAboutIgnoredParts(const Context& c, const SceneContent& content) {
    if (content.skinned > 0) {
        c.warnings.push_back(c.file + ": ignored the skins of " + plural(content.skinned, "node") +
                             " (each mesh is drawn rigid in its bind pose, moved by its node)");
    }
    if (content.cameras > 0) {
        c.warnings.push_back(c.file + ": ignored " + plural(content.cameras, "camera node"));
    }
}

// ---- One copy of the model, then its replicas ----------------------------------------------

bool isMirrored(const glm::dmat4& world) { return glm::determinant(glm::dmat3(world)) < 0.0; }

// "model.gltf: node 1 ('Wall')", the name when it has one: where an error in a node's extras is.
std::string nodeWhere(const Context& c, uint32_t node) {
    const std::string& name = c.model.nodes[node].name;
    return c.file + ": node " + std::to_string(node) + (name.empty() ? "" : " ('" + name + "')");
}

// A node's own occluder role, from its extras: {"occsim_occluder": "always" | "never" |
// "by_size"} (docs/scenario-gltf.md); none when it says nothing. Anything else there is an error
// naming the file and the node.
std::optional<OccluderRole> nodeOccluderRole(const Context& c, uint32_t node) {
    if (node >= c.model.nodes.size()) return std::nullopt;
    const tg::Value& extras = c.model.nodes[node].extras;
    if (!extras.IsObject() || !extras.Has("occsim_occluder")) return std::nullopt;
    const tg::Value& v = extras.Get("occsim_occluder");
    const std::string role = v.IsString() ? v.Get<std::string>() : std::string();
    if (role == "always") return OccluderRole::Always;
    if (role == "never") return OccluderRole::Never;
    if (role == "by_size") return OccluderRole::BySize;
    const std::string got = v.IsString()   ? "\"" + role + "\""
                            : v.IsBool()   ? std::string("a boolean")
                            : v.IsNumber() ? std::string("a number")
                            : v.IsObject() ? std::string("an object")
                            : v.IsArray()  ? std::string("an array")
                                           : std::string("null");
    throw GltfError(nodeWhere(c, node) +
                    ": extras.occsim_occluder: expected \"always\", \"never\" or \"by_size\", "
                    "got " +
                    got);
}

// A node's own occluder mesh, from its extras: {"occsim_occluder_mesh": <index of a mesh of the
// file>} (docs/scenario-gltf.md); none when it says nothing. Anything else there is an error
// naming the file and the node.
std::optional<uint32_t> nodeOccluderMesh(const Context& c, uint32_t node) {
    if (node >= c.model.nodes.size()) return std::nullopt;
    const tg::Value& extras = c.model.nodes[node].extras;
    if (!extras.IsObject() || !extras.Has("occsim_occluder_mesh")) return std::nullopt;
    const tg::Value& v = extras.Get("occsim_occluder_mesh");
    const size_t meshes = c.model.meshes.size();
    if (v.IsNumber()) {
        const double index = v.GetNumberAsDouble();
        if (index >= 0.0 && index < static_cast<double>(meshes) && index == std::floor(index))
            return static_cast<uint32_t>(index);
    }
    std::string got = "no number";
    if (v.IsString()) got = "\"" + v.Get<std::string>() + "\"";
    if (v.IsNumber()) {
        const double number = v.GetNumberAsDouble();
        got = number == std::floor(number) && std::abs(number) < 1e15
                  ? std::to_string(static_cast<int64_t>(number))
                  : std::to_string(number);
    }
    throw GltfError(nodeWhere(c, node) +
                    ": extras.occsim_occluder_mesh: expected the index of one of the file's " +
                    std::to_string(meshes) + (meshes == 1 ? " mesh" : " meshes") + ", got " + got);
}

// An object's name: its node's, else its mesh's, else the node's index.
std::string nodeLabel(const Context& c, uint32_t node, size_t mesh) {
    if (node < c.model.nodes.size() && !c.model.nodes[node].name.empty())
        return c.model.nodes[node].name;
    if (mesh < c.model.meshes.size() && !c.model.meshes[mesh].name.empty())
        return c.model.meshes[mesh].name;
    return "node " + std::to_string(node);
}

// One object per mesh node; each glTF mesh is converted once however many nodes use it, and
// output in the variants (as is, mirrored) that nodes use. Object transforms include the spec's
// scale but not its offset.
SourceOutput placeModel(const Context& c, const SceneContent& content, double scale,
                        std::vector<uint32_t>& object_visit) {
    const size_t mesh_count = c.model.meshes.size();
    std::vector<uint8_t> used(mesh_count * 2, 0);  // [mesh * 2 + mirrored]
    // Per instance, the mesh its node names as its occluder (output like a drawn mesh, mirrored
    // where the node is).
    std::vector<std::optional<uint32_t>> occluder_of(content.instances.size());
    for (size_t i = 0; i < content.instances.size(); ++i) {
        const MeshInstance& instance = content.instances[i];
        const size_t mirrored = isMirrored(instance.world) ? 1 : 0;
        used[instance.mesh * 2 + mirrored] = 1;
        occluder_of[i] = nodeOccluderMesh(c, content.visits[instance.visit].node);
        if (occluder_of[i]) used[*occluder_of[i] * 2 + mirrored] = 1;
    }
    SourceOutput out;
    constexpr uint32_t kNone = UINT32_MAX;
    std::vector<uint32_t> output_mesh(mesh_count * 2, kNone);
    for (size_t mesh = 0; mesh < mesh_count; ++mesh) {
        if (!used[mesh * 2] && !used[mesh * 2 + 1]) continue;
        MeshData converted = convertMesh(c, mesh);
        if (converted.indices.empty()) continue;  // its warnings say why
        if (used[mesh * 2 + 1]) {
            output_mesh[mesh * 2 + 1] = static_cast<uint32_t>(out.meshes.size());
            out.meshes.push_back(reversedWinding(converted));
        }
        if (used[mesh * 2]) {
            output_mesh[mesh * 2] = static_cast<uint32_t>(out.meshes.size());
            out.meshes.push_back(std::move(converted));
        }
    }
    for (size_t i = 0; i < content.instances.size(); ++i) {
        const MeshInstance& instance = content.instances[i];
        const size_t mirrored = isMirrored(instance.world) ? 1 : 0;
        const uint32_t mesh = output_mesh[instance.mesh * 2 + mirrored];
        if (mesh == kNone) continue;
        PlacedObject object;
        object.mesh = mesh;
        object.name = nodeLabel(c, content.visits[instance.visit].node, instance.mesh);
        object.occluder = nodeOccluderRole(c, content.visits[instance.visit].node);
        if (occluder_of[i] && output_mesh[*occluder_of[i] * 2 + mirrored] != kNone)
            object.occluder_mesh = output_mesh[*occluder_of[i] * 2 + mirrored];
        object.position = scale * glm::dvec3(instance.world[3]);
        object.linear = glm::mat3(glm::dmat3(instance.world) * scale);
        out.objects.push_back(object);
        object_visit.push_back(instance.visit);
    }
    return out;
}

struct Copy {
    glm::dvec3 origin{0.0};
    double yaw = 0.0;  // radians about +y
};

// Where the copies go. Grid copy (i, j) sits at (i * spacing_x, 0, j * spacing_z), so copy
// (0, 0) is the model where the file put it.
std::vector<Copy> copyPlacements(const GltfReplication& r, const Aabb& model_bounds, uint64_t seed,
                                 glm::dvec2& grid_spacing) {
    std::vector<Copy> copies;
    switch (r.mode) {
        case GltfReplication::Mode::None:
            copies.push_back({});
            break;
        case GltfReplication::Mode::Grid: {
            const glm::dvec3 size(extent(model_bounds));
            grid_spacing = r.spacing_m > 0.0 ? glm::dvec2(r.spacing_m)
                                             : glm::dvec2(size.x * 1.1, size.z * 1.1);
            for (uint32_t j = 0; j < r.count_z; ++j) {
                for (uint32_t i = 0; i < r.count_x; ++i) {
                    copies.push_back({{i * grid_spacing.x, 0.0, j * grid_spacing.y}, 0.0});
                }
            }
            break;
        }
        case GltfReplication::Mode::Random: {
            Rng rng(seed);
            const glm::dvec3 lo(r.region.min), hi(r.region.max);
            for (uint32_t k = 0; k < r.count; ++k) {
                Copy copy;
                copy.origin = {rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y),
                               rng.uniform(lo.z, hi.z)};
                if (r.random_yaw) copy.yaw = rng.uniform(0.0, 2.0 * std::numbers::pi);
                copies.push_back(copy);
            }
            break;
        }
    }
    return copies;
}

// A closed loop around each grid copy along the middle of the streets between copies, at the
// height of the model's origin (its ground), for movers with motion "path".
std::vector<std::vector<glm::dvec3>> gridLanes(const std::vector<Copy>& copies,
                                               const Aabb& model_bounds, glm::dvec2 spacing,
                                               const glm::dvec3& offset) {
    const glm::dvec3 lo(model_bounds.min), hi(model_bounds.max);
    const double half_gap_x = 0.5 * (spacing.x - (hi.x - lo.x));
    const double half_gap_z = 0.5 * (spacing.y - (hi.z - lo.z));
    std::vector<std::vector<glm::dvec3>> lanes;
    if (!(half_gap_x > 0.0) || !(half_gap_z > 0.0)) return lanes;  // copies touch or overlap
    for (const Copy& copy : copies) {
        const glm::dvec3 o = offset + copy.origin;
        const double x0 = o.x + lo.x - half_gap_x, x1 = o.x + hi.x + half_gap_x;
        const double z0 = o.z + lo.z - half_gap_z, z1 = o.z + hi.z + half_gap_z;
        lanes.push_back({{x0, o.y, z0}, {x0, o.y, z1}, {x1, o.y, z1}, {x1, o.y, z0}});
    }
    return lanes;
}

SourceOutput replicate(SourceOutput model, const GltfSourceSpec& spec, uint64_t seed,
                       const std::string& file) {
    // One copy's bounds about its own origin: small, so float holds them.
    const Aabb model_bounds = floatBox(sourceBounds(model));
    glm::dvec2 spacing(0.0);
    const std::vector<Copy> copies = copyPlacements(spec.replicate, model_bounds, seed, spacing);
    if (copies.size() * model.objects.size() > kMaxObjects) {
        fail(file, "replication would make " +
                       std::to_string(copies.size() * model.objects.size()) +
                       " objects; the limit is " + std::to_string(kMaxObjects));
    }
    std::vector<PlacedObject> one_copy = std::move(model.objects);
    model.objects.clear();
    model.objects.reserve(copies.size() * one_copy.size());
    model.model_copies.reserve(copies.size());
    for (const Copy& copy : copies) {
        const size_t k = model.model_copies.size();
        model.model_copies.push_back({spec.offset + copy.origin, copy.yaw});
        const glm::dmat3 yaw(glm::rotate(glm::dmat4(1.0), copy.yaw, glm::dvec3(0, 1, 0)));
        for (PlacedObject object : one_copy) {
            // Copies share their nodes' names: the copy's number tells them apart.
            if (copies.size() > 1) object.name += " #" + std::to_string(k);
            object.position = spec.offset + copy.origin + yaw * object.position;
            object.linear = glm::mat3(yaw) * object.linear;
            model.objects.push_back(object);
        }
    }
    if (spec.replicate.mode == GltfReplication::Mode::Grid) {
        model.lanes = gridLanes(copies, model_bounds, spacing, spec.offset);
    }
    // The sun once (it lights the whole scene, whatever a copy's yaw); a spot light with each
    // copy, moved and turned as the copy is.
    std::vector<LightSpec> one_copy_lights = std::move(model.lights);
    model.lights.clear();
    for (const LightSpec& light : one_copy_lights) {
        if (light.type == LightType::Directional) model.lights.push_back(light);
    }
    for (const Copy& copy : copies) {
        const glm::dmat3 yaw(glm::rotate(glm::dmat4(1.0), copy.yaw, glm::dvec3(0, 1, 0)));
        for (LightSpec light : one_copy_lights) {
            if (light.type != LightType::Spot) continue;
            light.position = spec.offset + copy.origin + yaw * light.position;
            light.direction = yaw * light.direction;
            model.lights.push_back(light);
        }
    }
    model.region = sourceBounds(model);
    return model;
}

}  // namespace

SourceOutput loadGltfSource(const GltfSourceSpec& spec, uint64_t seed) {
    const std::string file = spec.path.string();
    std::vector<std::string> warnings;
    const tg::Model model = readModel(spec.path, file, warnings);
    checkRequiredExtensions(model, file);
    const Context c{model, file, warnings};
    const SceneContent content = flattenScene(c);
    warnAboutIgnoredParts(c, content);
    auto animated = std::make_shared<AnimatedModel>();
    animated->animations = readAnimations(c);
    SourceOutput out = placeModel(c, content, spec.scale, animated->object_visit);
    if (out.objects.empty()) {
        // The first warning usually says why (e.g. only LINES primitives); it has the file already.
        const std::string why =
            warnings.empty() ? "" : "; " + warnings.front().substr(file.size() + 2);
        fail(file, "no triangles to draw (" + plural(content.instances.size(), "mesh node") +
                       " in the scene" + why + ")");
    }
    out.lights = convertLights(c, content.lights, spec.scale, spec.lights);
    animated->nodes = content.nodes;
    animated->visits = content.visits;
    animated->scale = spec.scale;
    out.model = std::move(animated);
    out = replicate(std::move(out), spec, seed, file);
    out.warnings = std::move(warnings);
    return out;
}

}  // namespace occsim
