// See light_view.h.
#include "sim/world/light_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/world/camera_path.h"

namespace occsim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The light-space bounds of points.
template <class Points>
void lightBounds(const LightBox& box, const Points& points, glm::dvec3& lo, glm::dvec3& hi) {
    lo = glm::dvec3(kInf);
    hi = glm::dvec3(-kInf);
    for (const glm::dvec3& p : points) {
        const glm::dvec3 l = toLightSpace(box, p);
        lo = glm::min(lo, l);
        hi = glm::max(hi, l);
    }
}

}  // namespace

std::array<glm::dvec3, 8> viewFrustumCorners(const glm::dvec3& eye, const glm::dvec3& target,
                                             double fov_y_deg, double aspect, double near_m,
                                             double far_m) {
    const glm::dvec3 forward = glm::normalize(target - eye);
    // The camera's own axes by the rule the renderer's camera uses (makeFrameView).
    const glm::dvec3 right = glm::normalize(glm::cross(forward, cameraWorldUp(forward)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double tan_half = std::tan(glm::radians(fov_y_deg) * 0.5);
    std::array<glm::dvec3, 8> corners;
    const double distances[2] = {near_m, far_m};
    for (int plane = 0; plane < 2; ++plane) {
        const double d = distances[plane];
        const double h = d * tan_half, w = h * aspect;
        const glm::dvec3 c = eye + d * forward;
        corners[plane * 4 + 0] = c - w * right - h * up;
        corners[plane * 4 + 1] = c + w * right - h * up;
        corners[plane * 4 + 2] = c + w * right + h * up;
        corners[plane * 4 + 3] = c - w * right + h * up;
    }
    return corners;
}

glm::dvec3 toLightSpace(const LightBox& box, const glm::dvec3& world) {
    return {glm::dot(world, box.right), glm::dot(world, box.up), glm::dot(world, box.forward)};
}

LightBox fitDirectionalLight(const glm::dvec3& direction, const std::array<glm::dvec3, 8>& corners,
                             const WorldBox& scene) {
    LightBox box;
    box.forward = glm::normalize(direction);
    // Any basis across the light will do: from world +y, or +z where the light is nearly vertical.
    const glm::dvec3 reference =
        std::abs(box.forward.y) > 0.9 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(0.0, 1.0, 0.0);
    box.right = glm::normalize(glm::cross(box.forward, reference));
    box.up = glm::cross(box.right, box.forward);
    if (isEmpty(scene)) return box;
    std::array<glm::dvec3, 8> scene_corners;
    for (int i = 0; i < 8; ++i) {
        scene_corners[i] = {(i & 1) ? scene.max.x : scene.min.x,
                            (i & 2) ? scene.max.y : scene.min.y,
                            (i & 4) ? scene.max.z : scene.min.z};
    }
    glm::dvec3 view_lo, view_hi, scene_lo, scene_hi;
    lightBounds(box, corners, view_lo, view_hi);
    lightBounds(box, scene_corners, scene_lo, scene_hi);
    box.min =
        glm::dvec3(std::max(view_lo.x, scene_lo.x), std::max(view_lo.y, scene_lo.y), scene_lo.z);
    box.max = glm::dvec3(std::min(view_hi.x, scene_hi.x), std::min(view_hi.y, scene_hi.y),
                         std::min(view_hi.z, scene_hi.z));
    // Empty when the camera's frustum and the scene overlap nowhere across the light, or the
    // frustum lies wholly before or beyond the scene along it.
    box.empty = !(box.min.x <= box.max.x && box.min.y <= box.max.y && box.min.z <= box.max.z &&
                  view_lo.z <= scene_hi.z);
    return box;
}

void lightSpaceBounds(const LightBox& box, const glm::dvec3& lo, const glm::dvec3& hi,
                      glm::dvec3& min, glm::dvec3& max) {
    const glm::dvec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    const glm::dvec3 axes[3] = {box.right, box.up, box.forward};
    for (int a = 0; a < 3; ++a) {
        const double c = glm::dot(centre, axes[a]), e = glm::dot(half, glm::abs(axes[a]));
        min[a] = c - e;
        max[a] = c + e;
    }
}

int firstShadowLight(const std::vector<LightSpec>& lights) {
    for (size_t i = 0; i < lights.size(); ++i) {
        if (lights[i].type == LightType::Directional && lights[i].casts_shadows) {
            return static_cast<int>(i);
        }
    }
    return -1;
}

void objectsInLightBox(const LightBox& box, std::span<const Aabb> boxes,
                       const glm::dvec3& culling_origin, std::vector<uint32_t>& out) {
    out.clear();
    if (box.empty) return;
    for (size_t o = 0; o < boxes.size(); ++o) {
        glm::dvec3 min, max;
        lightSpaceBounds(box, glm::dvec3(boxes[o].min) + culling_origin,
                         glm::dvec3(boxes[o].max) + culling_origin, min, max);
        if (glm::all(glm::lessThanEqual(min, box.max)) &&
            glm::all(glm::greaterThanEqual(max, box.min))) {
            out.push_back(static_cast<uint32_t>(o));
        }
    }
}

}  // namespace occsim
