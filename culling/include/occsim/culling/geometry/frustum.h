// View-frustum tests. A Frustum is six inward-facing planes extracted from an OpenGL-convention
// view-projection matrix (clip z in [-w, w]); the renderer may use another depth mapping
// (reverse-Z) but culling always works on this one.
//
// Every box test runs one kernel (classifyBox below) over a FrustumPlanes table: the planes'
// coefficients and the absolute values of their normals, which a culler builds once when it begins
// a frame (PreparedView, occsim/culling/contract/culler.h). The batch form runs it over
// structure-of-arrays boxes; the single-box calls are thin wrappers over it, so no path can drift
// from another.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "occsim/culling/geometry/aabb.h"
#include "occsim/culling/geometry/query_box.h"  // nearPlaneTouchesBox, which every culler uses

namespace occsim {

enum class FrustumTest : uint8_t { Outside = 0, Intersects = 1, Inside = 2 };

struct Frustum {
    // (a, b, c, d): a point p is on the inner side when dot(abc, p) + d >= 0. Normalised.
    // Order: left, right, bottom, top, near, far.
    glm::vec4 planes[6];
};

Frustum frustumFromViewProjection(const glm::mat4& view_projection);
// The same, extracted in double and stored in float. With a deep depth range the far plane is
// the difference of two rows that nearly cancel (its normal is ~2 near / far of their size): in
// float that difference is rounding noise (near 10^-3 m, far 10^6 m: 2e-9 against errors of
// 1e-7), and the noisy far plane culls visible objects. Build view frustums with this one.
Frustum frustumFromViewProjection(const glm::dmat4& view_projection);

// The plane table the kernel reads, one array per coefficient so that the kernel's six-plane loop
// reads registers, not a pointer the output might alias. Building it costs about as much as one
// box test, so a frame builds it once rather than per box.
struct FrustumPlanes {
    float a[6];
    float b[6];
    float c[6];
    float d[6];
    float abs_a[6];
    float abs_b[6];
    float abs_c[6];
};

inline FrustumPlanes planeTableOf(const Frustum& f) {
    FrustumPlanes k{};
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

// The kernel: a FrustumTest value as an integer, so the batch loop stays in plain arithmetic.
// Inline, because the cullers call it once per node and object
// and a call would cost as much as the test.
inline int classifyBox(const FrustumPlanes& k, float min_x, float min_y, float min_z, float max_x,
                       float max_y, float max_z) {
    // The centre/half-extent form of the p-vertex/n-vertex test: for a plane (n, d), the box's
    // farthest point along n lies at dot(n, centre) + d + dot(|n|, half_extent), its nearest at
    // the same minus that radius. Pure arithmetic, no per-plane choice of corner, so the batch
    // loop vectorises. Scaling each bound by 0.5 before adding keeps huge finite boxes from
    // overflowing to inf.
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
        // Written so that NaN makes the comparisons false: a NaN distance can neither prove a box
        // outside a plane nor inside it.
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

// Conservative: Outside only when the box is fully outside one plane. The form every culler uses
// per node and object, with the table its frame built.
inline FrustumTest classify(const FrustumPlanes& k, const Aabb& box) {
    return static_cast<FrustumTest>(
        classifyBox(k, box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z));
}

// The same for a one-off test (pictures, tests): builds the table for this one box.
FrustumTest classify(const Frustum& f, const Aabb& box);

// Batch form over boxes stored as separate arrays of min and max corners (structure of arrays):
// out[i] = classify(k, {min[i], max[i]}) for i in [0, count).
void classifyBatch(const FrustumPlanes& k, const float* min_x, const float* min_y,
                   const float* min_z, const float* max_x, const float* max_y, const float* max_z,
                   size_t count, FrustumTest* out);
void classifyBatch(const Frustum& f, const float* min_x, const float* min_y, const float* min_z,
                   const float* max_x, const float* max_y, const float* max_z, size_t count,
                   FrustumTest* out);

// The distance from the eye to a corner of the near-plane rectangle of a symmetric perspective
// projection (vertical field of view fov_y, width / height = aspect), with 1% to spare: the
// near_radius of nearPlaneTouchesBox() (query_box.h, the rule on the box as a device draws it).
inline double nearPlaneCornerDistance(double near_plane, double fov_y_radians, double aspect) {
    const double tan_half = std::tan(0.5 * fov_y_radians);
    return 1.01 * near_plane * std::sqrt(1.0 + tan_half * tan_half * (1.0 + aspect * aspect));
}

}  // namespace occsim
