// View-frustum plane extraction (Gribb & Hartmann, "Fast extraction of viewing frustum planes from
// the world-view-projection matrix", 2001) and conservative box classification.
//
// The kernel itself (classifyBox) is inline in frustum.h: the cullers call it per node and object
// with the plane table their frame built, and classify() and classifyBatch() here wrap the same
// function, so no path can drift from another.
#include "occsim/culling/geometry/frustum.h"

#include <cmath>

namespace occsim {

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

Frustum frustumFromViewProjection(const glm::dmat4& view_projection) {
    glm::dvec4 row[4];
    for (int i = 0; i < 4; ++i) {
        row[i] = glm::dvec4(view_projection[0][i], view_projection[1][i], view_projection[2][i],
                            view_projection[3][i]);
    }
    const glm::dvec4 planes[6] = {row[3] + row[0], row[3] - row[0], row[3] + row[1],
                                  row[3] - row[1], row[3] + row[2], row[3] - row[2]};
    Frustum f{};
    for (int p = 0; p < 6; ++p) {
        const double length = glm::length(glm::dvec3(planes[p]));
        f.planes[p] = glm::vec4(length > 0.0 ? planes[p] / length : planes[p]);
    }
    return f;
}

FrustumTest classify(const Frustum& f, const Aabb& box) { return classify(planeTableOf(f), box); }

void classifyBatch(const FrustumPlanes& planes, const float* __restrict min_x,
                   const float* __restrict min_y, const float* __restrict min_z,
                   const float* __restrict max_x, const float* __restrict max_y,
                   const float* __restrict max_z, size_t count, FrustumTest* __restrict out) {
    // A local copy: the loop then reads the table from registers instead of reloading it through
    // a reference the output array might alias.
    const FrustumPlanes k = planes;
    for (size_t i = 0; i < count; ++i) {
        out[i] = static_cast<FrustumTest>(
            classifyBox(k, min_x[i], min_y[i], min_z[i], max_x[i], max_y[i], max_z[i]));
    }
}

void classifyBatch(const Frustum& f, const float* min_x, const float* min_y, const float* min_z,
                   const float* max_x, const float* max_y, const float* max_z, size_t count,
                   FrustumTest* out) {
    classifyBatch(planeTableOf(f), min_x, min_y, min_z, max_x, max_y, max_z, count, out);
}

}  // namespace occsim
