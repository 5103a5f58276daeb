// Checks on a generated mesh, for the primitives' and the generators' tests: its signed volume,
// whether it is closed and consistently oriented, whether its faces point outward; and where a
// placed object's box lies.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <map>
#include <string>
#include <tuple>
#include <utility>

#include "occsim/culling/geometry/aabb.h"
#include "render/mesh_data.h"
#include "sim/scene/scene_source.h"

namespace occsim::testing {

// The volume the mesh encloses, positive when its triangles wind counter-clockwise seen from
// outside.
inline double signedVolume(const MeshData& m) {
    double v = 0.0;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]),
            c(m.positions[m.indices[t + 2]]);
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

// Every directed edge a -> b (by position, to a tenth of a millimetre, so that flat-shaded meshes
// with split vertices still match) is cancelled by an edge b -> a of another triangle: the mesh
// is a union of closed, consistently oriented surfaces.
inline ::testing::AssertionResult isClosed(const MeshData& m) {
    using Key = std::tuple<long, long, long>;
    const auto key = [&](uint32_t i) {
        const glm::vec3 p = m.positions[i] * 1e4f;
        return Key(std::lround(p.x), std::lround(p.y), std::lround(p.z));
    };
    std::map<std::pair<Key, Key>, int> balance;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        for (int e = 0; e < 3; ++e) {
            const Key a = key(m.indices[t + e]), b = key(m.indices[t + (e + 1) % 3]);
            if (a < b) {
                ++balance[{a, b}];
            } else {
                --balance[{b, a}];
            }
        }
    }
    size_t open = 0;
    for (const auto& [edge, count] : balance) open += count != 0;
    if (open == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << open << " of " << balance.size() << " edges unmatched";
}

// Indices in range, whole triangles, one finite unit normal per position, positive volume.
inline void expectValidMesh(const MeshData& m, const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_FALSE(m.indices.empty());
    ASSERT_EQ(m.indices.size() % 3, 0u);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        ASSERT_TRUE(std::isfinite(m.positions[i].x) && std::isfinite(m.positions[i].y) &&
                    std::isfinite(m.positions[i].z));
        ASSERT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-4f) << "normal " << i;
    }
    EXPECT_GT(signedVolume(m), 0.0);
    EXPECT_TRUE(isClosed(m));
}

// Each triangle's geometric normal (from its counter-clockwise winding) points the same way as
// the normals stored at its corners: the faces are outward and front-facing from outside.
inline void expectFaceNormalsAgree(const MeshData& m) {
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                        c = m.positions[m.indices[t + 2]];
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k) {
            ASSERT_GT(glm::dot(n, m.normals[m.indices[t + k]]), 0.0f) << "triangle " << t / 3;
        }
    }
}

// A placed object's box in the source's frame: its mesh's bounds transformed and moved.
inline Aabb objectBox(const SourceOutput& s, const PlacedObject& o) {
    glm::mat4 m(o.linear);
    m[3] = glm::vec4(0, 0, 0, 1);
    Aabb box = transformAabb(meshBounds(s.meshes.at(o.mesh)), m);
    box.min = glm::vec3(glm::dvec3(box.min) + o.position);
    box.max = glm::vec3(glm::dvec3(box.max) + o.position);
    return box;
}

}  // namespace occsim::testing
