// Simple closed meshes for procedural scenes and spawned movers. All are centred on the origin in
// x and z and stand on y = 0 (their base at y = 0, their top at y = height), outward normals,
// counter-clockwise front faces.
#pragma once

#include "render/mesh_data.h"

#include <cstdint>

namespace occsim {

// An axis-aligned box of the given size, 12 triangles, flat-shaded (24 vertices).
MeshData makeBox(glm::vec3 size);

// A capped cylinder along y, `segments` around (>= 3): 4 * segments triangles.
MeshData makeCylinder(float radius, float height, uint32_t segments);

// A UV sphere of the given radius sitting on y = 0, `segments` around (>= 3) and `rings` from
// pole to pole (>= 2): 2 * segments * (rings - 1) triangles.
MeshData makeSphere(float radius, uint32_t segments, uint32_t rings);

// Appends `part` to `mesh`, moved by `offset` (to build one mesh from several pieces).
void appendMesh(MeshData& mesh, const MeshData& part, glm::vec3 offset);

}  // namespace occsim
