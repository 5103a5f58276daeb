#include "sim/view/node_boxes.h"

#include <array>

namespace occsim {
namespace {

// Hierarchy-culled nodes below an occluded one (NotReached) and nodes only passed through are left
// out: the occluded ancestor's box already encloses the former, and the latter would wrap the
// whole scene in nested boxes. For the same reason only the outermost frustum-culled node of a
// subtree is drawn, and only the innermost visible ones (see frontier()).
constexpr std::array<NodeBoxClass, 4> kShown = {{
    {NodeClass::FrustumCulled, "frustum culled"},
    {NodeClass::OcclusionCulled, "queried occluded"},
    {NodeClass::DrawnAfterQuery, "queried visible"},
    {NodeClass::DrawnWithoutQuery, "drawn without a query"},
}};

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

bool visible(NodeClass c) {
    return c == NodeClass::DrawnAfterQuery || c == NodeClass::DrawnWithoutQuery;
}

// Whether node n's box is worth drawing: not nested in a box of the same meaning. A hierarchical
// culler finds every ancestor of a visible node visible too; the deepest ones say where.
bool frontier(const BspTree& tree, std::span<const NodeClass> classes, uint32_t n) {
    const BspNode& node = tree.node(n);
    switch (classes[n]) {
        case NodeClass::FrustumCulled:
            return node.parent == BspTree::kNone ||
                   classes[node.parent] != NodeClass::FrustumCulled;
        case NodeClass::DrawnAfterQuery:
            if (node.isLeaf()) return true;
            return !visible(classes[node.child[0]]) && !visible(classes[node.child[1]]);
        default:
            return true;
    }
}

}  // namespace

std::span<const NodeBoxClass> shownNodeBoxClasses() { return kShown; }

void drawBoxWireframe(RasterCanvas& canvas, const ViewSetup& view, double near_m, const Aabb& box,
                      Rgb colour) {
    if (!isFiniteAndOrdered(box)) return;
    drawBox(canvas, Projector{view, near_m, double(canvas.width()), double(canvas.height())}, box,
            colour);
}

void drawNodeBoxes(RasterCanvas& canvas, const BspTree& tree, std::span<const NodeClass> classes,
                   const ViewSetup& view, double near_m) {
    const Projector p{view, near_m, double(canvas.width()), double(canvas.height())};
    for (const NodeBoxClass& shown : kShown) {
        const Rgb colour = nodeClassColour(shown.node_class);
        for (uint32_t n = 0; n < tree.nodeCount() && n < classes.size(); ++n) {
            if (classes[n] != shown.node_class || !frontier(tree, classes, n)) continue;
            const Aabb& b = tree.bounds(n);
            if (isFiniteAndOrdered(b)) drawBox(canvas, p, b, colour);
        }
    }
}

}  // namespace occsim
