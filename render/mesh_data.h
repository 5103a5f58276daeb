// Triangle meshes as plain CPU data: what scene sources produce and what the renderer uploads.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "occsim/culling/geometry/aabb.h"

namespace occsim {

struct MeshData {
    std::vector<glm::vec3> positions;  // model space, metres
    std::vector<glm::vec3> normals;    // unit length, one per position
    std::vector<uint32_t> indices;     // triangle list, counter-clockwise front faces

    uint32_t triangleCount() const { return static_cast<uint32_t>(indices.size() / 3); }
};

// The model-space bounds of a mesh's vertices (empty for a mesh without vertices).
inline Aabb meshBounds(const MeshData& mesh) {
    Aabb b;
    for (const glm::vec3& p : mesh.positions) extend(b, p);
    return b;
}

}  // namespace occsim
