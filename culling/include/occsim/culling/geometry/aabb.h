// Axis-aligned bounding boxes. Units are scene units (metres), world space, float.
// An "empty" box has min = +inf and max = -inf so that extending it by any box yields that box.
#pragma once

#include <cmath>
#include <glm/glm.hpp>
#include <limits>

namespace occsim {

struct Aabb {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};
};

inline Aabb makeAabb(glm::vec3 min, glm::vec3 max) { return Aabb{min, max}; }

// True when every coordinate is finite and min <= max on every axis (zero extent allowed).
inline bool isFiniteAndOrdered(const Aabb& b) {
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(b.min[i]) || !std::isfinite(b.max[i]) || b.min[i] > b.max[i])
            return false;
    }
    return true;
}

inline bool isEmpty(const Aabb& b) {
    return !(b.min.x <= b.max.x && b.min.y <= b.max.y && b.min.z <= b.max.z);
}

inline void extend(Aabb& b, const Aabb& o) {
    b.min = glm::min(b.min, o.min);
    b.max = glm::max(b.max, o.max);
}

inline void extend(Aabb& b, glm::vec3 p) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
}

inline glm::vec3 center(const Aabb& b) { return 0.5f * (b.min + b.max); }
inline glm::vec3 extent(const Aabb& b) { return b.max - b.min; }

// Closed containment: a box touching the outer box's faces is still inside.
inline bool contains(const Aabb& outer, const Aabb& inner) {
    return glm::all(glm::lessThanEqual(outer.min, inner.min)) &&
           glm::all(glm::lessThanEqual(inner.max, outer.max));
}

inline bool contains(const Aabb& b, glm::vec3 p) {
    return glm::all(glm::lessThanEqual(b.min, p)) && glm::all(glm::lessThanEqual(p, b.max));
}

inline bool overlaps(const Aabb& a, const Aabb& b) {
    return glm::all(glm::lessThanEqual(a.min, b.max)) && glm::all(glm::lessThanEqual(b.min, a.max));
}

// Squared distance from a point to the box (0 inside).
inline float distanceSquared(const Aabb& b, glm::vec3 p) {
    glm::vec3 d = glm::max(glm::max(b.min - p, p - b.max), glm::vec3(0.0f));
    return glm::dot(d, d);
}

// The box of a local-space box under an affine transform (Arvo's method: exact for the 8 corners).
inline Aabb transformAabb(const Aabb& local, const glm::mat4& m) {
    glm::vec3 t(m[3]);
    Aabb out{t, t};
    for (int col = 0; col < 3; ++col) {
        for (int row = 0; row < 3; ++row) {
            float a = m[col][row] * local.min[col];
            float b = m[col][row] * local.max[col];
            out.min[row] += a < b ? a : b;
            out.max[row] += a < b ? b : a;
        }
    }
    return out;
}

}  // namespace occsim
