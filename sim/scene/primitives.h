// Simple closed meshes for procedural scenes and spawned movers. All are centred on the origin in
// x and z and stand on y = 0 (their base at y = 0, their top at y = height), outward normals,
// counter-clockwise front faces.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "render/mesh_data.h"
#include "sim/scene/scene_source.h"

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

// Appends the axis-aligned box with corners `lo` and `hi` (lo < hi on every axis) to `mesh`:
// 12 triangles, the building block of the generators' composite meshes (windows, books, beams).
void appendBox(MeshData& mesh, glm::vec3 lo, glm::vec3 hi);

// A diagonal scale matrix, the `linear` part that stretches a unit mesh to a size.
glm::mat3 scaleMatrix(glm::vec3 scale);

// An object drawing `unit_box_mesh` (makeBox({1, 1, 1})) stretched to fill the box lo..hi, so that
// every slab, wall and board of a generated scene shares one 12-triangle mesh.
PlacedObject placeUnitBox(uint32_t unit_box_mesh, glm::dvec3 lo, glm::dvec3 hi);

}  // namespace occsim
