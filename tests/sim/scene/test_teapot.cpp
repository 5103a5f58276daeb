#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <stdexcept>

#include "sim/scene/teapot.h"

namespace occsim {
namespace {

// Divergence theorem: the volume enclosed by an outward-wound closed mesh is positive.
double signedVolume(const MeshData& mesh) {
    double volume = 0.0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 p0(mesh.positions[mesh.indices[t]]);
        const glm::dvec3 p1(mesh.positions[mesh.indices[t + 1]]);
        const glm::dvec3 p2(mesh.positions[mesh.indices[t + 2]]);
        volume += glm::dot(p0, glm::cross(p1, p2)) / 6.0;
    }
    return volume;
}

TEST(Teapot, TriangleAndVertexCountsFollowTheDocumentedFormula) {
    for (uint32_t level : {1u, 2u, 3u, 8u, 16u}) {
        const MeshData mesh = tessellateTeapot(level);
        const uint64_t expectedTriangles = 64ull * level * level - 8ull * level;
        EXPECT_EQ(teapotTriangleCount(level), expectedTriangles) << "level " << level;
        EXPECT_EQ(mesh.triangleCount(), expectedTriangles) << "level " << level;
        EXPECT_EQ(mesh.indices.size() % 3, 0u);
        EXPECT_EQ(mesh.positions.size(), 32ull * (level + 1) * (level + 1)) << "level " << level;
        EXPECT_EQ(mesh.positions.size(), teapotVertexCount(level));
        EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
        for (uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size());
    }
}

TEST(Teapot, NoTriangleIsDegenerate) {
    const MeshData mesh = tessellateTeapot(8);
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const glm::vec3 p0 = mesh.positions[mesh.indices[t]];
        const glm::vec3 p1 = mesh.positions[mesh.indices[t + 1]];
        const glm::vec3 p2 = mesh.positions[mesh.indices[t + 2]];
        EXPECT_GT(glm::length(glm::cross(p1 - p0, p2 - p0)), 0.0f) << "triangle " << t / 3;
    }
}

TEST(Teapot, PositionsAndNormalsAreFiniteAndNormalsUnitLength) {
    for (uint32_t level : {1u, 4u, 16u}) {
        const MeshData mesh = tessellateTeapot(level);
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            const glm::vec3 p = mesh.positions[i];
            const glm::vec3 n = mesh.normals[i];
            ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
            ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z))
                << "level " << level << " vertex " << i;
            EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f) << "level " << level << " vertex " << i;
        }
    }
}

TEST(Teapot, BoundingBoxHasUnitHeightBottomAtZeroAndIsCentredInXZ) {
    for (uint32_t level : {1u, 4u, 16u}) {
        const Aabb b = meshBounds(tessellateTeapot(level));
        EXPECT_EQ(b.min.y, 0.0f) << "level " << level;
        EXPECT_FLOAT_EQ(b.max.y, 1.0f) << "level " << level;
        EXPECT_NEAR(center(b).x, 0.0f, 1e-6f) << "level " << level;
        EXPECT_NEAR(center(b).z, 0.0f, 1e-6f) << "level " << level;
        // The teapot is wider (spout to handle, along x) than deep (along z), and not flat.
        EXPECT_GT(extent(b).x, extent(b).z);
        EXPECT_GT(extent(b).z, 1.0f);
    }
}

TEST(Teapot, IsUprightWithSpoutTowardsPlusXAndHandleTowardsMinusX) {
    const MeshData mesh = tessellateTeapot(16);
    std::size_t minX = 0, maxX = 0, top = 0, bottom = 0;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 p = mesh.positions[i];
        if (p.x < mesh.positions[minX].x) minX = i;
        if (p.x > mesh.positions[maxX].x) maxX = i;
        if (p.y > mesh.positions[top].y) top = i;
        if (p.y < mesh.positions[bottom].y) bottom = i;
    }
    // The lid-top and bottom-centre poles lie on the teapot's vertical axis. The spout reaches
    // farther from it than the handle, so the bounding-box centre (x = 0) is on the spout side
    // and the axis sits slightly towards -x.
    const glm::vec3 pTop = mesh.positions[top], pBottom = mesh.positions[bottom];
    EXPECT_EQ(pTop.y, 1.0f);
    EXPECT_EQ(pBottom.y, 0.0f);
    EXPECT_NEAR(pTop.x, pBottom.x, 1e-6f);
    EXPECT_NEAR(pTop.z, 0.0f, 1e-6f);
    EXPECT_NEAR(pBottom.z, 0.0f, 1e-6f);
    EXPECT_LT(pTop.x, 0.0f);
    EXPECT_GT(pTop.x, -0.1f);
    // The lid-top pole faces up, the bottom pole faces down.
    EXPECT_GT(mesh.normals[top].y, 0.999f);
    EXPECT_LT(mesh.normals[bottom].y, -0.999f);
    // The spout tip (dataset z ~2.45 of 3.15) is the farthest point along +x; the handle's outer
    // bend (dataset z ~1.8) is the farthest along -x.
    EXPECT_GT(mesh.positions[maxX].y, 0.7f);
    EXPECT_GT(mesh.positions[minX].y, 0.45f);
    EXPECT_LT(mesh.positions[minX].y, 0.7f);
    EXPECT_GT(mesh.positions[maxX].x, 0.9f);
    EXPECT_LT(mesh.positions[minX].x, -0.9f);
}

TEST(Teapot, SignedVolumeIsPositiveAndStableAcrossLevels) {
    const double v8 = signedVolume(tessellateTeapot(8));
    const double v16 = signedVolume(tessellateTeapot(16));
    EXPECT_GT(v8, 0.0);
    EXPECT_GT(v16, 0.0);
    EXPECT_LT(std::abs(v8 - v16) / v16, 0.02) << "v8 " << v8 << " v16 " << v16;
    // Sanity: the body is roughly a 1.3 x 0.8 x 1.3 (unit-height) bulb, so well below its box.
    EXPECT_GT(v16, 0.2);
    EXPECT_LT(v16, 1.0);
}

TEST(Teapot, FaceNormalsAgreeWithAveragedVertexNormals) {
    for (uint32_t level : {4u, 8u, 16u}) {
        const MeshData mesh = tessellateTeapot(level);
        std::size_t agree = 0;
        for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
            const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1];
            const uint32_t i2 = mesh.indices[t + 2];
            const glm::vec3 face = glm::cross(mesh.positions[i1] - mesh.positions[i0],
                                              mesh.positions[i2] - mesh.positions[i0]);
            const glm::vec3 avg = mesh.normals[i0] + mesh.normals[i1] + mesh.normals[i2];
            if (glm::dot(face, avg) > 0.0f) ++agree;
        }
        const double fraction = static_cast<double>(agree) / mesh.triangleCount();
        EXPECT_GT(fraction, 0.95) << "level " << level;
    }
}

TEST(Teapot, SameLevelGivesIdenticalMeshes) {
    const MeshData a = tessellateTeapot(5);
    const MeshData b = tessellateTeapot(5);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.indices, b.indices);
}

TEST(Teapot, RejectsLevelZeroAndLevelsAboveTheMaximum) {
    EXPECT_THROW(tessellateTeapot(0), std::invalid_argument);
    EXPECT_THROW(tessellateTeapot(kTeapotMaxLevel + 1), std::invalid_argument);
}

}  // namespace
}  // namespace occsim
