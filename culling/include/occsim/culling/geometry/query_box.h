// The box a device rasterises for an occlusion query, and the one rule that decides whether a box
// may be queried at all. Both live here, beside each other, so that the device that draws the
// box (render/gl_renderer.cpp) and every culler that asks (through nearPlaneTouchesBox) reason
// about the same box: the one drawn, dilation included.
//
// Why the rule must see the dilation: a query box is drawn a little larger than the bound it
// stands for, so that edges shared with occluders and the float rounding of its corners never
// lose a sample. If the eye lies within that margin (but outside the bound), the drawn box
// contains the eye, only its far faces rasterise, the query can return zero samples for a
// visible subtree, and a culler would drop it. So the rule tests the dilated box, in double, with
// room for the float eye the cullers see.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "occsim/culling/geometry/aabb.h"

namespace occsim {

// How far (metres) every face of a query box is pushed outward before it is drawn. Two terms:
// - a fixed part of 10^-4 of the box's diagonal, at least 10^-4 m and at most 1 cm, so that a box
//   of zero extent still rasterises and a face that coincides with an occluder's surface passes
//   the depth test. Bounded above: it used to grow with the diagonal without limit (100 m for a
//   node 10^6 m across), which is what let a large node's drawn box swallow the eye;
// - 10^-6 of the distance from the eye to the box's centre (about eight float steps): the
//   rounding of the corners, drawn in float relative to the eye, scales with that distance.
// `lo`, `hi`: the box; `eye`: the eye, all in one frame (any origin).
inline double queryBoxPad(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& eye) {
    constexpr double kRelativeToSize = 1e-4, kMinSize = 1.0, kMaxSize = 100.0;
    constexpr double kRelativeToDistance = 1e-6;
    const double diagonal = glm::length(hi - lo);
    const double size =
        std::clamp(std::isfinite(diagonal) ? diagonal : kMaxSize, kMinSize, kMaxSize);
    return kRelativeToSize * size + kRelativeToDistance * glm::length(0.5 * (lo + hi) - eye);
}

// The distance from `eye` to the box as a device draws it for a query (grown by queryBoxPad on
// every side); 0 when the drawn box contains the eye, NaN when a coordinate is not a number.
inline double distanceToDrawnQueryBox(const Aabb& box, const glm::dvec3& eye) {
    const glm::dvec3 lo(box.min), hi(box.max);
    const double pad = queryBoxPad(lo, hi, eye);
    const glm::dvec3 below = (lo - pad) - eye;  // > 0 where the eye is below the box
    const glm::dvec3 above = eye - (hi + pad);  // > 0 where the eye is above it
    const glm::dvec3 gap = glm::max(glm::max(below, above), glm::dvec3(0.0));
    return glm::length(gap);
}

// The rule: the eye is so close to the box as a device draws it for a query (dilation included)
// that the near plane may cut it, or the eye is inside it. Such a query would be clipped and
// could report zero samples while the box is visible, so callers must render instead of
// querying. near_radius is the distance from the eye to a corner of the near-plane rectangle
// (nearPlaneCornerDistance, frustum.h). The eye handed to cullers is a float, rounded from the
// camera's double position; the comparison leaves room for that rounding (half a float step per
// axis of the eye's own magnitude) and for the box's corners rounded to float when drawn. A box
// whose distance is not a number (a NaN coordinate) counts as touching: nothing is known about
// where it is, so it must be drawn, never queried.
inline bool nearPlaneTouchesBox(const Aabb& box, glm::vec3 eye, float near_radius) {
    const glm::dvec3 e(eye);
    constexpr double kFloatStep = 1.0 / (1 << 23);
    const double eye_rounding = kFloatStep * (std::abs(e.x) + std::abs(e.y) + std::abs(e.z));
    const double distance = distanceToDrawnQueryBox(box, e);
    const double corner_rounding = kFloatStep * distance;
    return !(distance - eye_rounding - corner_rounding > static_cast<double>(near_radius));
}

}  // namespace occsim
