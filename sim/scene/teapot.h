// The Utah teapot (Newell 1975), tessellated from its 32 bicubic Bezier patches into a MeshData.
//
// Conventions of the result (see teapot.cpp for details):
//  - y-up (the dataset is z-up; (x, y, z) -> (x, z, -y), a proper rotation, so handedness and
//    winding are preserved). The spout points along +x, the handle along -x.
//  - Scaled uniformly so that the mesh's bounding-box height (y extent) is exactly 1.0, with the
//    bottom at y = 0 and the bounding box centred on x = 0, z = 0.
//  - Counter-clockwise front faces seen from outside; normals are the analytic patch normals
//    (cross product of the partial derivatives), unit length, pointing outward.
//
// Counts for level L (segments per patch side):
//  - vertices:  32 * (L + 1)^2        (each patch has its own grid; nothing is shared)
//  - triangles: 64 * L^2 - 8 * L      (2 * L^2 per patch; the 8 patches that meet at the lid-top
//                                      and bottom poles each drop the L zero-area triangles whose
//                                      edge would lie on the pole)
#pragma once

#include <cstdint>

#include "render/mesh_data.h"

namespace occsim {

inline constexpr uint32_t kTeapotPatchCount = 32;
inline constexpr uint32_t kTeapotMaxLevel = 1024;  // keeps every count far inside uint32_t

constexpr uint64_t teapotVertexCount(uint32_t level) {
    return uint64_t{kTeapotPatchCount} * (uint64_t{level} + 1) * (uint64_t{level} + 1);
}

constexpr uint64_t teapotTriangleCount(uint32_t level) {
    return 64 * uint64_t{level} * level - 8 * uint64_t{level};
}

// Tessellates every patch into a level x level grid of quads (two triangles each).
// Throws std::invalid_argument when level is 0 or greater than kTeapotMaxLevel.
MeshData tessellateTeapot(uint32_t level);

}  // namespace occsim
