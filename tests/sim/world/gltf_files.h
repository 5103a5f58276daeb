// What the glTF tests share: the real files in scenarios/assets, loading a file or a synthetic
// document through the world, and the checks every loaded scene must pass.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <glm/glm.hpp>
#include <string>

#include "gltf_builder.h"
#include "sim/scene/gltf_source.h"
#include "sim/world/world.h"

namespace occsim::gltf_files {

using namespace testing_gltf;

inline const std::filesystem::path kAssets =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/assets";
inline const std::filesystem::path kTeapot = kAssets / "Teapot/teapot.gltf";
inline const std::filesystem::path kSubpass =
    kAssets / "SubpassSceneOpaque/subpass_scene_opaque.gltf";
inline const std::filesystem::path kHouse = kAssets / "FZK-Haus/AC14-FZK-Haus.glb";

inline SourceOutput load(const std::filesystem::path& path, double scale = 1.0,
                         glm::dvec3 offset = glm::dvec3(0.0), GltfReplication replicate = {},
                         uint64_t seed = 1) {
    GltfSourceSpec spec;
    spec.path = path;
    spec.scale = scale;
    spec.offset = offset;
    spec.replicate = replicate;
    return loadGltfSource(spec, seed);
}

inline uint64_t drawnTriangles(const SourceOutput& out) {
    uint64_t total = 0;
    for (const PlacedObject& o : out.objects) total += out.meshes.at(o.mesh).triangleCount();
    return total;
}

// What every loaded source must satisfy whatever the file: finite positions, unit finite
// normals (one per position), whole triangles, indices in range, every mesh used.
inline void expectWellFormed(const SourceOutput& out) {
    std::vector<uint8_t> used(out.meshes.size(), 0);
    for (const PlacedObject& o : out.objects) {
        ASSERT_LT(o.mesh, out.meshes.size());
        used[o.mesh] = 1;
    }
    for (size_t m = 0; m < out.meshes.size(); ++m) {
        const MeshData& mesh = out.meshes[m];
        EXPECT_TRUE(used[m]) << "mesh " << m << " is used by no object";
        ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << "mesh " << m;
        ASSERT_EQ(mesh.indices.size() % 3, 0u) << "mesh " << m;
        EXPECT_GT(mesh.indices.size(), 0u) << "mesh " << m;
        for (const glm::vec3& p : mesh.positions) {
            ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
        }
        for (const glm::vec3& n : mesh.normals) {
            ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
            ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f) << "mesh " << m;
        }
        for (uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size()) << "mesh " << m;
    }
}

inline void expectBoxNear(const Aabb& box, glm::vec3 min, glm::vec3 max, float tolerance) {
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(box.min[axis], min[axis], tolerance) << "min, axis " << axis;
        EXPECT_NEAR(box.max[axis], max[axis], tolerance) << "max, axis " << axis;
    }
}

// The geometric normal of triangle t of an object's mesh in world space (unnormalised).
inline glm::vec3 worldFaceNormal(const SourceOutput& out, const PlacedObject& o, size_t t) {
    const MeshData& mesh = out.meshes[o.mesh];
    const glm::vec3 a = o.linear * mesh.positions[mesh.indices[3 * t]];
    const glm::vec3 b = o.linear * mesh.positions[mesh.indices[3 * t + 1]];
    const glm::vec3 c = o.linear * mesh.positions[mesh.indices[3 * t + 2]];
    return glm::cross(b - a, c - a);
}

inline bool anyWarningContains(const SourceOutput& out, const std::string& text) {
    return std::any_of(out.warnings.begin(), out.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

inline std::string allWarnings(const SourceOutput& out) {
    std::string text;
    for (const std::string& w : out.warnings) text += w + "\n";
    return text;
}

// Loads a synthetic document through a temporary .gltf file.
inline SourceOutput loadText(const std::string& text, GltfReplication replicate = {},
                             uint64_t seed = 1, double scale = 1.0,
                             glm::dvec3 offset = glm::dvec3(0.0)) {
    TempDir dir;
    return load(dir.write("model.gltf", text), scale, offset, replicate, seed);
}

// The GltfError message of loading `path`, or "" when it loads.
inline std::string errorOf(const std::filesystem::path& path) {
    try {
        load(path);
    } catch (const GltfError& e) {
        return e.what();
    }
    return "";
}

inline std::string errorOfText(const std::string& text) {
    TempDir dir;
    return errorOf(dir.write("model.gltf", text));
}

}  // namespace occsim::gltf_files
