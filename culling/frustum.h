// View-frustum tests. A Frustum is six inward-facing planes extracted from an OpenGL-convention
// view-projection matrix (clip z in [-w, w]); the renderer may use another depth mapping (reverse-Z)
// but culling always works on this one. Batch kernels run over structure-of-arrays boxes; the
// single-box calls are thin wrappers over the same arithmetic.
#pragma once

#include "culling/aabb.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace occsim {

enum class FrustumTest : uint8_t { Outside = 0, Intersects = 1, Inside = 2 };

struct Frustum {
    // (a, b, c, d): a point p is on the inner side when dot(abc, p) + d >= 0. Normalised.
    // Order: left, right, bottom, top, near, far.
    glm::vec4 planes[6];
};

Frustum frustumFromViewProjection(const glm::mat4& view_projection);

// Conservative: Outside only when the box is fully outside one plane.
FrustumTest classify(const Frustum& f, const Aabb& box);

// Batch form over boxes stored as separate arrays of min and max corners (structure of arrays):
// out[i] = classify(f, {min[i], max[i]}) for i in [0, count).
void classifyBatch(const Frustum& f, const float* min_x, const float* min_y, const float* min_z,
                   const float* max_x, const float* max_y, const float* max_z, size_t count,
                   FrustumTest* out);

// The eye is so close to the box that the near plane may cut it (or the eye is inside it): an
// occlusion query on such a box would be clipped and could report zero samples while the box is
// visible, so callers must render instead of querying. near_radius is the distance from the eye to
// a corner of the near-plane rectangle.
// The distance from the eye to a corner of the near-plane rectangle of a symmetric perspective
// projection (vertical field of view fov_y, width / height = aspect), with 1% to spare: the
// near_radius of nearPlaneTouchesBox().
inline double nearPlaneCornerDistance(double near_plane, double fov_y_radians, double aspect) {
    const double tan_half = std::tan(0.5 * fov_y_radians);
    return 1.01 * near_plane * std::sqrt(1.0 + tan_half * tan_half * (1.0 + aspect * aspect));
}

// A box whose distance is not a number (a NaN coordinate) counts as touching: nothing is known
// about where it is, so it must be drawn, never queried.
inline bool nearPlaneTouchesBox(const Aabb& box, glm::vec3 eye, float near_radius) {
    return !(distanceSquared(box, eye) > near_radius * near_radius);
}

}  // namespace occsim
