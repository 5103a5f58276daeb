// World boxes: an object's box under its pose, rounded outward to float, and the check that stops
// a run when a placement or a motion took one out of finite coordinates.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <string>

#include "sim/world/world.h"

namespace occsim {

glm::dmat4 modelMatrix(const ObjectPose& pose) {
    return glm::translate(glm::dmat4(1.0), pose.position) *
           glm::dmat4(glm::mat4_cast(pose.rotation)) * glm::dmat4(glm::mat4(pose.linear));
}

namespace {

// Float conversions that never move a bound inward.
float floatAtMost(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
    return f;
}

float floatAtLeast(double v) {
    float f = static_cast<float>(v);
    if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}

}  // namespace

Aabb worldBox(const Aabb& mesh_bounds, const ObjectPose& pose, const glm::dvec3& origin) {
    // Arvo's transform of the local box by the linear part, in double, then the position relative
    // to the origin: exact to double precision, and only then rounded (outward) to float.
    ObjectPose at_origin = pose;
    at_origin.position = glm::dvec3(0.0);
    const glm::dmat4 m = modelMatrix(at_origin);
    glm::dvec3 lo = pose.position - origin, hi = lo;
    for (int col = 0; col < 3; ++col) {
        for (int row = 0; row < 3; ++row) {
            const double a = m[col][row] * mesh_bounds.min[col];
            const double b = m[col][row] * mesh_bounds.max[col];
            lo[row] += std::min(a, b);
            hi[row] += std::max(a, b);
        }
    }
    Aabb box;
    for (int axis = 0; axis < 3; ++axis) {
        box.min[axis] = floatAtMost(lo[axis]);
        box.max[axis] = floatAtLeast(hi[axis]);
    }
    return box;
}

namespace {

[[noreturn]] void throwNotFinite(const WorldState& state, uint32_t object, uint32_t frame,
                                 const std::string& how) {
    const ObjectPose& pose = state.poses[object];
    const glm::dvec3& p = pose.position;
    // A scale (a glTF animation's, a node's) can overflow the box as surely as a position: the
    // largest stretch of the pose's linear part says which it was.
    double scale = 0.0;
    for (int c = 0; c < 3; ++c) scale = std::max(scale, glm::length(glm::dvec3(pose.linear[c])));
    char figures[240];
    std::snprintf(figures, sizeof figures, "its position is (%g, %g, %g), its scale %g", p.x, p.y,
                  p.z, scale);
    throw MotionError("frame " + std::to_string(frame) + ": object " + std::to_string(object) +
                      " " + how + " left finite float coordinates (" + figures +
                      "); the run stops here");
}

}  // namespace

void requireFiniteBoxes(const WorldState& state, uint32_t frame) {
    if (frame == 0) {
        for (uint32_t o = 0; o < state.boxes.size(); ++o) {
            if (!isFiniteAndOrdered(state.boxes[o])) throwNotFinite(state, o, frame, "as placed");
        }
        return;
    }
    for (size_t m = 0; m < state.movers.size(); ++m) {
        const uint32_t o = state.movers[m].object;
        if (state.movers[m].copy < 0 && !isFiniteAndOrdered(state.boxes[o])) {
            throwNotFinite(state, o, frame, "moved by mover " + std::to_string(m));
        }
    }
    for (const uint32_t o : state.moved) {
        if (!isFiniteAndOrdered(state.boxes[o])) {
            throwNotFinite(state, o, frame,
                           "moved with its glTF model (animation or whole-copy mover)");
        }
    }
}

}  // namespace occsim
