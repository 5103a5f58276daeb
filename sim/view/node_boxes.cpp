#include "sim/view/node_boxes.h"

#include <array>

#include "sim/output/box_wireframe.h"

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

void drawNodeBoxes(RasterCanvas& canvas, const BspTree& tree, std::span<const NodeClass> classes,
                   const ViewSetup& view, double near_m) {
    for (const NodeBoxClass& shown : kShown) {
        const Rgb colour = nodeClassColour(shown.node_class);
        for (uint32_t n = 0; n < tree.nodeCount() && n < classes.size(); ++n) {
            if (classes[n] != shown.node_class || !frontier(tree, classes, n)) continue;
            drawBoxWireframe(canvas, view, near_m, tree.bounds(n), colour);
        }
    }
}

}  // namespace occsim
