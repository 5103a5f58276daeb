// Pieces every hierarchical culler shares: front-to-back child order, frustum classification
// that is inherited by the children of a node fully inside, and drawing one node's own objects
// with a per-object frustum test. Every test here reads the plane table of the frame's
// PreparedView (culler.h): there is no overload taking a Frustum, so no culler can rebuild the
// table per box by accident. The helpers that take the PreparedView record the frustum's
// decisions (a node or an object culled by it) in its decision log, when it has one.
#pragma once

#include <cstdint>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/tree/bsp_tree.h"

namespace occsim {

struct NodeVisit {
    uint32_t node;
    bool inside_frustum;  // an ancestor (or the node) is fully inside: no frustum test needed
};

// Pushes the children of `node` onto a LIFO stack so that the child on the eye's side of the
// split plane is popped first (front to back).
inline void pushChildrenFrontToBack(const BspTree& tree, uint32_t node, glm::vec3 eye,
                                    bool inside_frustum, std::vector<NodeVisit>& stack) {
    const BspNode& n = tree.node(node);
    if (n.isLeaf()) return;
    const bool eye_below = eye[n.axis] < n.split;
    const uint32_t first = n.child[eye_below ? 0 : 1];
    const uint32_t second = n.child[eye_below ? 1 : 0];
    stack.push_back({second, inside_frustum});
    stack.push_back({first, inside_frustum});
}

// Outside: skip the subtree. Otherwise reports whether the node is fully inside (so its subtree
// needs no further frustum tests). Empty subtrees count as outside.
inline bool nodeInFrustum(const BspTree& tree, const NodeVisit& visit, const FrustumPlanes& frustum,
                          bool* fully_inside) {
    const Aabb& b = tree.bounds(visit.node);
    if (isEmpty(b)) return false;
    if (visit.inside_frustum) {
        *fully_inside = true;
        return true;
    }
    const FrustumTest t = classify(frustum, b);
    *fully_inside = t == FrustumTest::Inside;
    return t != FrustumTest::Outside;
}

// Front-to-back traversal of the nodes that pass the frustum: `visit(visit)` is called with the
// node's inherited "fully inside" flag set, and returns true to descend into its children.
template <class Visit>
void traverseFrontToBack(const BspTree& tree, const PreparedView& view,
                         std::vector<NodeVisit>& stack, Visit&& visit) {
    stack.clear();
    stack.push_back({tree.root(), false});
    while (!stack.empty()) {
        NodeVisit node = stack.back();
        stack.pop_back();
        bool inside = false;
        if (!nodeInFrustum(tree, node, view.frustum, &inside)) {
            recordDecision(view.decisions, QueryTag::node(node.node),
                           decisionOf(DecisionKind::FrustumCulled));
            continue;
        }
        node.inside_frustum = inside;
        if (visit(node)) pushChildrenFrontToBack(tree, node.node, view.eye, inside, stack);
    }
}

// Calls fn(object) for each object stored in `node` itself (not its children) whose box passes
// the frustum (every one when the node is fully inside). The one loop behind drawing a node's
// objects, querying them as a virtual leaf, and deciding them one by one.
template <class Fn>
void forEachObjectInFrustum(const BspTree& tree, uint32_t node, const FrustumPlanes& frustum,
                            bool inside_frustum, Fn&& fn) {
    for (uint32_t o = tree.firstObject(node); o != BspTree::kNone; o = tree.nextObject(o)) {
        if (inside_frustum || classify(frustum, tree.objectBox(o)) != FrustumTest::Outside) fn(o);
    }
}

// The same, recording each object the frustum culls in the view's decision log.
template <class Fn>
void forEachObjectInFrustum(const BspTree& tree, uint32_t node, const PreparedView& view,
                            bool inside_frustum, Fn&& fn) {
    for (uint32_t o = tree.firstObject(node); o != BspTree::kNone; o = tree.nextObject(o)) {
        if (inside_frustum || classify(view.frustum, tree.objectBox(o)) != FrustumTest::Outside) {
            fn(o);
        } else {
            recordDecision(view.decisions, QueryTag::object(o),
                           decisionOf(DecisionKind::FrustumCulled));
        }
    }
}

// Draws the objects stored in `node` itself (not its children) that pass the frustum.
inline void drawNodeObjects(const BspTree& tree, uint32_t node, const FrustumPlanes& frustum,
                            bool inside_frustum, RenderDevice& device) {
    forEachObjectInFrustum(tree, node, frustum, inside_frustum,
                           [&device](uint32_t o) { device.drawObject(o); });
}

// The same, recording `why` for the node's objects and the frustum's decision for each it culls.
inline void drawNodeObjects(const BspTree& tree, uint32_t node, const PreparedView& view,
                            bool inside_frustum, RenderDevice& device, const Decision& why) {
    recordDecision(view.decisions, QueryTag::nodeObjects(node), why);
    forEachObjectInFrustum(tree, node, view, inside_frustum,
                           [&device](uint32_t o) { device.drawObject(o); });
}

}  // namespace occsim
