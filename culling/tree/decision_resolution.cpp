#include "occsim/culling/tree/decision_resolution.h"

namespace occsim {
namespace {

// A node's record on the objects stored in `node`: an object the frustum culled stays culled by
// its own record.
void applyToNodeObjects(const BspTree& tree, uint32_t node, const DecisionRecord& record,
                        std::vector<Decision>& out, std::vector<QueryTag>* subjects) {
    for (uint32_t o = tree.firstObject(node); o != BspTree::kNone; o = tree.nextObject(o)) {
        if (out[o].kind == DecisionKind::FrustumCulled) continue;
        out[o] = record.decision;
        if (subjects) (*subjects)[o] = record.subject;
    }
}

}  // namespace

void resolveDecisions(const BspTree& tree, std::span<const DecisionRecord> records,
                      std::vector<Decision>& out, std::vector<uint32_t>& stack,
                      std::vector<QueryTag>* subjects) {
    out.assign(tree.objectCount(), Decision{});
    if (subjects) subjects->assign(tree.objectCount(), QueryTag{});
    for (const DecisionRecord& r : records) {
        const uint32_t index = r.subject.index;
        switch (r.subject.subject) {
            case QueryTag::Subject::Object:
                if (index >= out.size()) break;
                out[index] = r.decision;
                if (subjects) (*subjects)[index] = r.subject;
                break;
            case QueryTag::Subject::NodeObjects:
                if (index < tree.nodeCount()) applyToNodeObjects(tree, index, r, out, subjects);
                break;
            case QueryTag::Subject::Node:
                if (index >= tree.nodeCount()) break;
                stack.clear();
                stack.push_back(index);
                while (!stack.empty()) {
                    const uint32_t n = stack.back();
                    stack.pop_back();
                    applyToNodeObjects(tree, n, r, out, subjects);
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
