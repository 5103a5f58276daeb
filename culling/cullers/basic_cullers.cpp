#include "culling/cullers/basic_cullers.h"

#include "occsim/culling/declaration/culler_row.h"
namespace occsim {

void VfcCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    view_ = prepareView(frame);
    const Decision why = decisionOf(DecisionKind::DrawnNoTest);
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        drawNodeObjects(tree, visit.node, view_, visit.inside_frustum, device, why);
        return true;
    });
}

void StopAndWaitCuller::cullAndRender(const BspTree& tree, const CullFrame& frame,
                                      RenderDevice& device) {
    view_ = prepareView(frame);
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        const Aabb& box = tree.bounds(visit.node);
        if (nearPlaneTouchesBox(box, frame.view.eye, frame.view.near_radius)) {
            drawNodeObjects(tree, visit.node, view_, visit.inside_frustum, device,
                            decisionOf(DecisionKind::DrawnNearPlane));
            return true;
        }
        const QueryAnswer answer =
            device.takeAnswer(device.issueQuery(box, QueryTag::node(visit.node)));
        const Decision why = answeredDecision(frame.frame_index, answer);
        if (!answer.visible) {
            recordDecision(view_.decisions, QueryTag::node(visit.node), why);
            return false;  // occluded: skip the subtree
        }
        drawNodeObjects(tree, visit.node, view_, visit.inside_frustum, device, why);
        return true;
    });
}

void IdealCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    view_ = prepareView(frame);
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        // Every object of the node is the oracle's to decide: those ground truth saw are drawn.
        recordDecision(view_.decisions, QueryTag::nodeObjects(visit.node),
                       decisionOf(DecisionKind::CulledByOracle));
        for (uint32_t o = tree.firstObject(visit.node); o != BspTree::kNone;
             o = tree.nextObject(o)) {
            if (o < frame.ground_truth_visible.size() && frame.ground_truth_visible[o]) {
                recordDecision(view_.decisions, QueryTag::object(o),
                               decisionOf(DecisionKind::DrawnByOracle));
                device.drawObject(o);
            }
        }
        return true;
    });
}

void IdealBoxCuller::cullAndRender(const BspTree& tree, const CullFrame& frame,
                                   RenderDevice& device) {
    view_ = prepareView(frame);
    tested_.clear();
    queries_.clear();
    const auto seen = [&](uint32_t o) {
        return o < frame.ground_truth_visible.size() && frame.ground_truth_visible[o] != 0;
    };
    // The visible objects first: their depth is the frame's final depth.
    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        forEachObjectInFrustum(tree, visit.node, view_, visit.inside_frustum, [&](uint32_t o) {
            if (seen(o)) {
                recordDecision(view_.decisions, QueryTag::object(o),
                               decisionOf(DecisionKind::DrawnByOracle));
                device.drawObject(o);
            } else {
                tested_.push_back(o);
            }
        });
        return true;
    });
    // Every other box against it; a box the near plane may cut is drawn, as every culler must.
    size_t kept = 0;
    for (const uint32_t o : tested_) {
        const Aabb& box = tree.objectBox(o);
        if (nearPlaneTouchesBox(box, frame.view.eye, frame.view.near_radius)) {
            recordDecision(view_.decisions, QueryTag::object(o),
                           decisionOf(DecisionKind::DrawnNearPlane));
            device.drawObject(o);
            continue;
        }
        tested_[kept++] = o;
        queries_.push_back(device.issueQuery(box, QueryTag::object(o)));
    }
    tested_.resize(kept);
    for (size_t i = 0; i < tested_.size(); ++i) {
        const QueryAnswer answer = device.takeAnswer(queries_[i]);
        recordDecision(view_.decisions, QueryTag::object(tested_[i]),
                       answeredDecision(frame.frame_index, answer));
        if (answer.visible) device.drawObject(tested_[i]);
    }
}

// --- Registration -------------------------------------------------------------------------------

CullerRow vfcRegistration() {
    CullerRow t;
    t.name = "vfc";
    t.summary = "view-frustum culling only (the reference)";
    t.speedup_reference = true;
    t.factory = [](const CullerContext&) -> std::unique_ptr<Culler> {
        return std::make_unique<VfcCuller>();
    };
    return t;
}

CullerRow stopAndWaitRegistration() {
    CullerRow t;
    t.name = "stop-and-wait";
    t.summary = "hierarchical queries, each result awaited";
    t.issues_queries = true;
    t.factory = [](const CullerContext&) -> std::unique_ptr<Culler> {
        return std::make_unique<StopAndWaitCuller>();
    };
    return t;
}

CullerRow idealRegistration() {
    CullerRow t;
    t.name = "ideal";
    t.summary = "draws what ground truth saw (the oracle)";
    t.oracle = true;
    t.factory = [](const CullerContext&) -> std::unique_ptr<Culler> {
        return std::make_unique<IdealCuller>();
    };
    return t;
}

CullerRow idealBoxRegistration() {
    CullerRow t;
    t.name = "ideal-box";
    t.summary =
        "draws every object whose box is visible against the visible objects' depth (the limit "
        "of box tests; an oracle)";
    // Its queries are exact: the approximation knobs, which issues_queries would let in, do not
    // apply to a bound.
    t.oracle = true;
    t.factory = [](const CullerContext&) -> std::unique_ptr<Culler> {
        return std::make_unique<IdealBoxCuller>();
    };
    return t;
}

}  // namespace occsim
