#include "culling/basic_cullers.h"

namespace occsim {

void VfcCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    stack_.clear();
    stack_.push_back({tree.root(), false});
    while (!stack_.empty()) {
        const NodeVisit visit = stack_.back();
        stack_.pop_back();
        bool inside = false;
        if (!nodeInFrustum(tree, visit, frame.view.frustum, &inside)) continue;
        drawNodeObjects(tree, visit.node, frame.view.frustum, inside, device);
        pushChildrenFrontToBack(tree, visit.node, frame.view.eye, inside, stack_);
    }
}

void StopAndWaitCuller::cullAndRender(const BspTree& tree, const CullFrame& frame,
                                      RenderDevice& device) {
    stack_.clear();
    stack_.push_back({tree.root(), false});
    while (!stack_.empty()) {
        const NodeVisit visit = stack_.back();
        stack_.pop_back();
        bool inside = false;
        if (!nodeInFrustum(tree, visit, frame.view.frustum, &inside)) continue;
        const Aabb& box = tree.bounds(visit.node);
        if (!nearPlaneTouchesBox(box, frame.view.eye, frame.view.near_radius)) {
            if (device.queryResult(device.issueQuery(box)) == 0) continue;
        }
        drawNodeObjects(tree, visit.node, frame.view.frustum, inside, device);
        pushChildrenFrontToBack(tree, visit.node, frame.view.eye, inside, stack_);
    }
}

void IdealCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    stack_.clear();
    stack_.push_back({tree.root(), false});
    while (!stack_.empty()) {
        const NodeVisit visit = stack_.back();
        stack_.pop_back();
        bool inside = false;
        if (!nodeInFrustum(tree, visit, frame.view.frustum, &inside)) continue;
        for (uint32_t o = tree.firstObject(visit.node); o != BspTree::kNone; o = tree.nextObject(o)) {
            if (o < frame.ground_truth_visible.size() && frame.ground_truth_visible[o]) {
                device.drawObject(o);
            }
        }
        pushChildrenFrontToBack(tree, visit.node, frame.view.eye, inside, stack_);
    }
}

}  // namespace occsim
