#include "sim/output/box_wireframe.h"

#include <array>

namespace occsim {
namespace {

struct Projector {
    const ViewSetup& view;
    double near_m;
    double width, height;

    // Tree bounds live in the culling frame (relative to view.box_origin), like query boxes.
    glm::vec4 toView(const glm::vec3& in_culling_frame) const {
        // Camera-relative in double, as the renderer does, then the rotation in float.
        const glm::vec3 relative(glm::dvec3(in_culling_frame) + view.box_origin - view.eye);
        return view.view_rotation * glm::vec4(relative, 1.0f);
    }
    glm::dvec2 toPixel(const glm::vec4& v) const {
        const glm::vec4 clip = view.projection * v;
        const double x = clip.x / clip.w, y = clip.y / clip.w;
        return {(x * 0.5 + 0.5) * width, (0.5 - y * 0.5) * height};  // canvas rows go down
    }
};

void drawEdge(RasterCanvas& canvas, const Projector& p, glm::vec4 a, glm::vec4 b, Rgb colour) {
    // Looking down -z: a point is in front of the near plane when -z >= near.
    const float near = static_cast<float>(p.near_m);
    const bool a_in = -a.z >= near, b_in = -b.z >= near;
    if (!a_in && !b_in) return;
    if (a_in != b_in) {
        const float t = (-near - a.z) / (b.z - a.z);
        const glm::vec4 cut = a + t * (b - a);
        (a_in ? b : a) = cut;
    }
    const glm::dvec2 pa = p.toPixel(a), pb = p.toPixel(b);
    canvas.line(pa.x, pa.y, pb.x, pb.y, colour);
}

void drawBox(RasterCanvas& canvas, const Projector& p, const Aabb& box, Rgb colour) {
    std::array<glm::vec4, 8> corners;
    for (int i = 0; i < 8; ++i) {
        corners[i] = p.toView({(i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                               (i & 4) ? box.max.z : box.min.z});
    }
    // The 12 edges: corner pairs that differ in one bit.
    for (int i = 0; i < 8; ++i) {
        for (int bit : {1, 2, 4}) {
            if (!(i & bit)) drawEdge(canvas, p, corners[i], corners[i | bit], colour);
        }
    }
}

}  // namespace

void drawBoxWireframe(RasterCanvas& canvas, const ViewSetup& view, double near_m, const Aabb& box,
                      Rgb colour) {
    if (!isFiniteAndOrdered(box)) return;
    drawBox(canvas, Projector{view, near_m, double(canvas.width()), double(canvas.height())}, box,
            colour);
}

}  // namespace occsim
