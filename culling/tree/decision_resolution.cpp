#include "occsim/culling/tree/decision_resolution.h"

namespace occsim {
namespace {

// A node's record on one of its objects: an object the frustum culled stays culled by it.
void applyFromNode(Decision& object, const Decision& decision) {
    if (object.kind != DecisionKind::FrustumCulled) object = decision;
}

void applyToNodeObjects(const BspTree& tree, uint32_t node, const Decision& decision,
                        std::vector<Decision>& out) {
    for (uint32_t o = tree.firstObject(node); o != BspTree::kNone; o = tree.nextObject(o))
        applyFromNode(out[o], decision);
}

}  // namespace

void resolveDecisions(const BspTree& tree, std::span<const DecisionRecord> records,
                      std::vector<Decision>& out, std::vector<uint32_t>& stack) {
    out.assign(tree.objectCount(), Decision{});
    for (const DecisionRecord& r : records) {
        const uint32_t index = r.subject.index;
        switch (r.subject.subject) {
            case QueryTag::Subject::Object:
                if (index < out.size()) out[index] = r.decision;
                break;
            case QueryTag::Subject::NodeObjects:
                if (index < tree.nodeCount()) applyToNodeObjects(tree, index, r.decision, out);
                break;
            case QueryTag::Subject::Node:
                if (index >= tree.nodeCount()) break;
                stack.clear();
                stack.push_back(index);
                while (!stack.empty()) {
                    const uint32_t n = stack.back();
                    stack.pop_back();
                    applyToNodeObjects(tree, n, r.decision, out);
                    const BspNode& node = tree.node(n);
                    if (!node.isLeaf()) {
                        stack.push_back(node.child[0]);
                        stack.push_back(node.child[1]);
                    }
                }
                break;
        }
    }
}

}  // namespace occsim
