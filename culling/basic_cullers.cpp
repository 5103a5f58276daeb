#include "culling/basic_cullers.h"

namespace occsim {

void VfcCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    view_ = prepareView(frame.view);
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        drawNodeObjects(tree, visit.node, view_.frustum, visit.inside_frustum, device);
        return true;
    });
}

void StopAndWaitCuller::cullAndRender(const BspTree& tree, const CullFrame& frame,
                                      RenderDevice& device) {
    view_ = prepareView(frame.view);
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        const Aabb& box = tree.bounds(visit.node);
        if (!nearPlaneTouchesBox(box, frame.view.eye, frame.view.near_radius) &&
            device.queryResult(device.issueQuery(box, QueryTag::node(visit.node))) == 0) {
            return false;  // occluded: skip the subtree
        }
        drawNodeObjects(tree, visit.node, view_.frustum, visit.inside_frustum, device);
        return true;
    });
}

void IdealCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    view_ = prepareView(frame.view);
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        for (uint32_t o = tree.firstObject(visit.node); o != BspTree::kNone; o = tree.nextObject(o)) {
            if (o < frame.ground_truth_visible.size() && frame.ground_truth_visible[o]) {
                device.drawObject(o);
            }
        }
        return true;
    });
}

}  // namespace occsim
