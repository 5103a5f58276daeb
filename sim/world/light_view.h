// A directional light's shadow view for one frame (docs/views.md): an orthographic box along the
// light that holds every point of the scene the camera can see and every point of the scene
// between the light and such a point, so that no caster of a visible shadow is left outside it.
// Pure geometry in double (world coordinates, 10^6 m from the origin included); the renderer
// turns the box into its projection.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "occsim/culling/geometry/aabb.h"
#include "sim/scenario/scene_specs.h"
#include "sim/scenario/view_specs.h"

namespace occsim {

// The 8 corners of a camera's view frustum to its far plane: near plane first, then far, each
// (-x -y), (+x -y), (+x +y), (-x +y) in the camera's own right and up.
std::array<glm::dvec3, 8> viewFrustumCorners(const glm::dvec3& eye, const glm::dvec3& target,
                                             double fov_y_deg, double aspect, double near_m,
                                             double far_m);

struct LightBox {
    // Light space: x along `right`, y along `up`, z along the light's direction of travel (depth,
    // growing away from the light), all measured from the world origin.
    glm::dvec3 right{1.0, 0.0, 0.0}, up{0.0, 1.0, 0.0}, forward{0.0, -1.0, 0.0};
    glm::dvec3 min{0.0}, max{0.0};  // the box in light space
    bool empty = true;              // the camera sees none of the scene's bounds: no shadow view
};

// A point in `box`'s light space.
glm::dvec3 toLightSpace(const LightBox& box, const glm::dvec3& world);

// The box for a light travelling along `direction` (non-zero): across the light, the light-space
// bounds of the camera's frustum (`corners`) and of the scene's bounds (`scene`) overlapped; in
// depth, from the scene's nearest point to the light, to the farther of what the camera and the
// scene reach, whichever ends first. A caster of a shadow on a visible point p lies on the ray
// from p toward the light, inside the scene: same x and y as p, a smaller depth, not beyond the
// scene's nearest. Empty when the two overlap nowhere across the light.
LightBox fitDirectionalLight(const glm::dvec3& direction, const std::array<glm::dvec3, 8>& corners,
                             const WorldBox& scene);

// The light-space bounds of a world box (lo, hi its corners), exact: its centre and half-extents
// projected on each of `box`'s axes.
void lightSpaceBounds(const LightBox& box, const glm::dvec3& lo, const glm::dvec3& hi,
                      glm::dvec3& min, glm::dvec3& max);

// The index into `lights` of the first shadow-casting directional light, the one a frame
// renders a shadow pass for (docs/views.md); -1 when there is none.
int firstShadowLight(const std::vector<LightSpec>& lights);

// Light-frustum culling of a shadow pass: the objects whose boxes (in the culling frame, which
// lies at `culling_origin` in the world) overlap `box` in light space, in index order; `out`
// replaced. A box's light-space bounds are exact (its centre and half-extents projected on each
// axis), so an object with a point inside the box is never left out.
void objectsInLightBox(const LightBox& box, std::span<const Aabb> boxes,
                       const glm::dvec3& culling_origin, std::vector<uint32_t>& out);

}  // namespace occsim
