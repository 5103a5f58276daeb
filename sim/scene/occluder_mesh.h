// Occluder meshes made for objects: fewer triangles than the object's own mesh, and inscribed in
// it, so that a software depth buffer (the `masked` culler) may rasterise them instead of the
// object at a fraction of the cost and still hide nothing the object does not.
//
// How: the mesh is welded (vertices at the same position, up to float rounding, made one: never
// wider, so that no hole or slit of the drawn mesh is closed) and must then be closed and
// consistently oriented (every edge shared by exactly two triangles, once each way); it is
// simplified with meshoptimizer (meshopt_simplify, about `triangle_share` of its triangles), and
// the simplified surface is moved inward along its vertex normals by the smallest of a few steps
// that keeps enough of it inside. Inscribed means here: every kept triangle lies strictly inside
// the object's solid, checked, not assumed: its three vertices are inside (a ray cast in three
// directions crosses the surface an odd number of times in each, with no ray grazing an edge)
// and it neither meets nor comes within `gap` of any triangle of the object as drawn, those the
// weld made degenerate included (the separating-axis test on triangle pairs). A triangle failing
// either check is dropped; dropping occluder triangles is always safe. So, seen from any eye
// outside the object's solid, every ray that reaches a kept triangle crosses the object's surface
// first: the occluder covers no pixel the object does not cover, and lies behind it where both do.
// From an eye inside the solid this does not hold: the culler uses the object's own mesh when the
// eye may be inside its box.
//
// Meshes that are not closed (a plane, an open teapot, most glTF scans), too small to gain
// (`min_triangles`), too large to check here (`max_triangles`, the check is quadratic), or whose
// occluder would cover too little of their outline from some side (`min_outline_share`: thin
// slats, fins, blades) get no occluder mesh: a one-line reason says why, and the object occludes
// with its own mesh.
#pragma once

#include <cstdint>
#include <string>

#include "render/mesh_data.h"

namespace occsim {

struct OccluderMeshSettings {
    double triangle_share = 0.1;  // the simplified mesh's target, of the source's triangles
    uint32_t min_triangles = 64;  // smaller meshes are their own occluders (a box: 12)
    uint32_t max_triangles = 60000;
    double kept_area_share = 0.9;  // the smallest inward step keeping this much area wins
    // A made occluder must cover this much of its object's outline seen along each of the three
    // axes and the four diagonals (sim/scene/outline_coverage.h), or it is refused: parts thinner
    // than twice the inward step become sheets that hide next to nothing edge-on. (A simplified
    // sphere covers 0.84 of its outline; 4 mm slats on two rails 0.12; docs/masked.md.)
    double min_outline_share = 0.25;
    uint32_t outline_resolution = 128;  // cells along each side of the outline's grid
};

struct OccluderMesh {
    MeshData mesh;        // no triangles when refused
    std::string refusal;  // why there is none (one line), empty when made
    uint32_t source_triangles = 0;
    double inward_step_m = 0.0;  // how far the simplified surface was moved in
    double kept_area_share = 0.0;
    uint32_t dropped_triangles = 0;  // checkAuthoredOccluder: its triangles left out
    double outline_share = 0.0;      // made: the least share of the outline it covers (above)
};

// The occluder mesh for `source`; never throws for bad geometry (it refuses instead).
OccluderMesh makeInscribedOccluder(const MeshData& source,
                                   const OccluderMeshSettings& settings = {});

// An occluder mesh someone made for `object` (a glTF node's extras.occsim_occluder_mesh), in
// the object's space, checked as a made one is: only its triangles that lie strictly inside the
// object's solid are kept (dropped_triangles counts the others). Refused, with the reason, when
// the object's mesh is not a closed solid (nothing to check it against) or none of its triangles
// lies inside, or when it has more triangles than the object's mesh (it would cost more than
// the mesh it stands in for; so max_triangles bounds both meshes and the check's cost).
OccluderMesh checkAuthoredOccluder(const MeshData& object, const MeshData& occluder,
                                   const OccluderMeshSettings& settings = {});

// The checks, for tests. `welded` indices into `positions`, closed and oriented.
bool pointInsideClosedMesh(const glm::dvec3& point, const std::vector<glm::dvec3>& positions,
                           const std::vector<uint32_t>& welded);
// Whether the triangles (a0, a1, a2) and (b0, b1, b2) meet or come within `gap` of each other
// (conservative: true unless some axis separates them by more than `gap`).
bool trianglesWithinGap(const glm::dvec3 (&a)[3], const glm::dvec3 (&b)[3], double gap);

}  // namespace occsim
