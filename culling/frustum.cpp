// View-frustum plane extraction (Gribb & Hartmann, "Fast extraction of viewing frustum planes from
// the world-view-projection matrix", 2001) and conservative box classification.
//
// Both classify() and classifyBatch() run the same inline kernel, so the batch path cannot drift
// from the single-box path. The kernel uses the centre/half-extent form of the p-vertex/n-vertex
// test: for a plane (n, d), the box's farthest point along n lies at distance
// dot(n, centre) + d + dot(|n|, half_extent) and its nearest point at the same minus the radius.
// That form is pure arithmetic (no per-plane choice of corner), so the compiler can vectorise the
// batch loop over structure-of-arrays boxes.
#include "culling/frustum.h"

#include <cmath>

namespace occsim {
namespace {

// Plane coefficients copied out of the Frustum into local scalars: the batch loop then reads them
// from registers instead of reloading through a pointer the output array might alias.
struct PlaneCoefficients {
    float a[6];
    float b[6];
    float c[6];
    float d[6];
    float abs_a[6];
    float abs_b[6];
    float abs_c[6];
};

inline PlaneCoefficients coefficientsOf(const Frustum& f) {
    PlaneCoefficients k{};
    for (int p = 0; p < 6; ++p) {
        k.a[p] = f.planes[p].x;
        k.b[p] = f.planes[p].y;
        k.c[p] = f.planes[p].z;
        k.d[p] = f.planes[p].w;
        k.abs_a[p] = std::fabs(k.a[p]);
        k.abs_b[p] = std::fabs(k.b[p]);
        k.abs_c[p] = std::fabs(k.c[p]);
    }
    return k;
}

// The shared kernel. Returns a FrustumTest value as an integer so the batch loop stays in plain
// arithmetic. Comparisons are written so that NaN makes them false: a NaN distance can neither
// prove a box outside a plane nor inside it.
inline int classifyBox(const PlaneCoefficients& k, float min_x, float min_y, float min_z,
                       float max_x, float max_y, float max_z) {
    // Scaling each bound by 0.5 before adding keeps huge finite boxes from overflowing to inf.
    const float centre_x = 0.5f * min_x + 0.5f * max_x;
    const float centre_y = 0.5f * min_y + 0.5f * max_y;
    const float centre_z = 0.5f * min_z + 0.5f * max_z;
    const float half_x = 0.5f * max_x - 0.5f * min_x;
    const float half_y = 0.5f * max_y - 0.5f * min_y;
    const float half_z = 0.5f * max_z - 0.5f * min_z;

    int outside_any = 0;
    int inside_all = 1;
    // Fully unrolled so that the batch loop, not this six-iteration loop, is what gets vectorised.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC unroll 6
#elif defined(__clang__)
#pragma clang loop unroll(full)
#endif
    for (int p = 0; p < 6; ++p) {
        const float distance = k.a[p] * centre_x + k.b[p] * centre_y + k.c[p] * centre_z + k.d[p];
        const float radius = k.abs_a[p] * half_x + k.abs_b[p] * half_y + k.abs_c[p] * half_z;
        outside_any |= static_cast<int>(distance + radius < 0.0f);  // p-vertex behind the plane
        inside_all &= static_cast<int>(distance - radius >= 0.0f);  // n-vertex in front of it
    }

    // NaN anywhere in the box: we know nothing, so never claim Outside (or Inside).
    const int has_nan = static_cast<int>(min_x != min_x) | static_cast<int>(min_y != min_y) |
                        static_cast<int>(min_z != min_z) | static_cast<int>(max_x != max_x) |
                        static_cast<int>(max_y != max_y) | static_cast<int>(max_z != max_z);
    // An inverted axis means an empty box (e.g. a default Aabb): nothing to see. Its negative
    // "radius" would otherwise make the plane tests meaningless.
    const int is_empty = static_cast<int>(min_x > max_x) | static_cast<int>(min_y > max_y) |
                         static_cast<int>(min_z > max_z);

    // Outside = 0, Intersects = 1, Inside = 2, computed with arithmetic instead of branches:
    // NaN wins (Intersects), then emptiness (Outside), then the plane tests.
    const int from_planes = (1 - outside_any) * (1 + inside_all) * (1 - is_empty);
    return has_nan + (1 - has_nan) * from_planes;
}

}  // namespace

Frustum frustumFromViewProjection(const glm::mat4& view_projection) {
    // glm is column-major: m[column][row]. Row i of the matrix maps a point to clip coordinate i.
    glm::vec4 row[4];
    for (int i = 0; i < 4; ++i) {
        row[i] = glm::vec4(view_projection[0][i], view_projection[1][i], view_projection[2][i],
                           view_projection[3][i]);
    }
    // A point is inside the clip volume when -w <= x, y, z <= w, i.e. w + x >= 0, w - x >= 0 ...
    Frustum f{};
    f.planes[0] = row[3] + row[0];  // left
    f.planes[1] = row[3] - row[0];  // right
    f.planes[2] = row[3] + row[1];  // bottom
    f.planes[3] = row[3] - row[1];  // top
    f.planes[4] = row[3] + row[2];  // near
    f.planes[5] = row[3] - row[2];  // far
    for (glm::vec4& plane : f.planes) {
        // Normalised so that plane distances are in world units; a degenerate matrix leaves the
        // plane as it is rather than dividing by zero.
        const float length = glm::length(glm::vec3(plane));
        if (length > 0.0f) plane /= length;
    }
    return f;
}

FrustumTest classify(const Frustum& f, const Aabb& box) {
    const PlaneCoefficients k = coefficientsOf(f);
    return static_cast<FrustumTest>(
        classifyBox(k, box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z));
}

void classifyBatch(const Frustum& f, const float* __restrict min_x, const float* __restrict min_y,
                   const float* __restrict min_z, const float* __restrict max_x,
                   const float* __restrict max_y, const float* __restrict max_z, size_t count,
                   FrustumTest* __restrict out) {
    const PlaneCoefficients k = coefficientsOf(f);
    for (size_t i = 0; i < count; ++i) {
        out[i] = static_cast<FrustumTest>(
            classifyBox(k, min_x[i], min_y[i], min_z[i], max_x[i], max_y[i], max_z[i]));
    }
}

}  // namespace occsim
