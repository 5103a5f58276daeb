#include "culling/cullers/conditional_culler.h"

#include <stdexcept>

#include "occsim/culling/declaration/culler_row.h"
#include "occsim/culling/declaration/option_table.h"
#include "occsim/culling/geometry/query_box.h"

namespace occsim {

void ConditionalCuller::queueQuery(const Aabb& box, QueryTag tag, std::span<const uint32_t> objects,
                                   RenderDevice& device) {
    const QueryId q = device.issueQuery(box, tag);
    pending_.push_back(
        {q, static_cast<uint32_t>(objects_.size()), static_cast<uint32_t>(objects.size())});
    objects_.insert(objects_.end(), objects.begin(), objects.end());
}

void ConditionalCuller::drawOldest(ConditionalRendering& conditional) {
    const Pending& p = pending_[head_++];
    conditional.drawIf(p.query, std::span<const uint32_t>(objects_).subspan(p.first, p.count),
                       options_.wait ? ConditionWait::Wait : ConditionWait::NoWait);
    conditional.release(p.query);
}

void ConditionalCuller::cullAndRender(const BspTree& tree, const CullFrame& frame,
                                      RenderDevice& device) {
    ConditionalRendering* conditional = device.conditionalRendering();
    if (conditional == nullptr) {
        throw std::logic_error(
            "conditional: the device offers no conditional rendering (a run refuses this culler "
            "before any work: requireDeviceFeatures)");
    }
    view_ = prepareView(frame);
    Decision conditional_why = decisionOf(DecisionKind::DrawnConditional);
    conditional_why.query_frame = static_cast<uint32_t>(frame.frame_index);
    const Decision near_why = decisionOf(DecisionKind::DrawnNearPlane);
    pending_.clear();
    objects_.clear();
    head_ = 0;
    const glm::vec3 eye = frame.view.eye;
    const float near_radius = frame.view.near_radius;

    traverseFrontToBack(tree, view_, stack_, [&](const NodeVisit& visit) {
        batch_.clear();
        Aabb around;  // the box around batch_
        forEachObjectInFrustum(tree, visit.node, view_, visit.inside_frustum, [&](uint32_t o) {
            const Aabb& box = tree.objectBox(o);
            if (nearPlaneTouchesBox(box, eye, near_radius)) {
                recordDecision(view_.decisions, QueryTag::object(o), near_why);
                device.drawObject(o);  // a query on it could say zero while it shows
            } else if (options_.node_queries) {
                batch_.push_back(o);
                extend(around, box);
            } else {
                recordDecision(view_.decisions, QueryTag::object(o), conditional_why);
                queueQuery(box, QueryTag::object(o), std::span<const uint32_t>(&o, 1), device);
            }
        });
        if (!batch_.empty()) {
            const bool near = nearPlaneTouchesBox(around, eye, near_radius);
            for (uint32_t o : batch_) {
                recordDecision(view_.decisions, QueryTag::object(o),
                               near ? near_why : conditional_why);
            }
            if (near) {
                for (uint32_t o : batch_) device.drawObject(o);
            } else {
                const QueryTag tag = tree.node(visit.node).isLeaf()
                                         ? QueryTag::node(visit.node)
                                         : QueryTag::nodeObjects(visit.node);
                queueQuery(around, tag, batch_, device);
            }
        }
        while (pending_.size() - head_ > options_.queries_ahead) drawOldest(*conditional);
        return true;
    });
    while (head_ < pending_.size()) drawOldest(*conditional);
}

// --- Registration -------------------------------------------------------------------------------

namespace {

const OptionTable<ConditionalOptions>& conditionalOptionTable() {
    using O = ConditionalOptions;
    static const OptionTable<O> table = {
        booleanOption(OCCSIM_OPTION_MEMBER(O, wait),
                      "the device waits for each answer (GL_QUERY_WAIT); false: it draws "
                      "unconditionally while the answer is not ready (GL_QUERY_NO_WAIT)"),
        booleanOption(OCCSIM_OPTION_MEMBER(O, node_queries),
                      "one query per node, on the box around its own objects in the frustum, "
                      "conditions all of them; false: one query per object"),
        switchable(
            tunable(integerOption(OCCSIM_OPTION_MEMBER(O, queries_ahead), "queries", 0, 65536,
                                  "queries issued before the draws conditioned on the "
                                  "oldest of them (time for its answer to arrive)"),
                    0, 256),
            0),
    };
    return table;
}

}  // namespace

CullerRow conditionalRegistration() {
    CullerRow t;
    t.name = "conditional";
    t.summary =
        "conditional rendering: a query per object (or node), drawn under its condition; the "
        "device decides, nothing is read back";
    // Its queries are never answered to it, so the approximation knobs (a pixel threshold,
    // stale answers) cannot apply: not `issues_queries` in the registry's sense.
    t.issues_queries = false;
    t.device_needs = kConditionalRendering;
    t.options = conditionalOptionTable().descriptor(ConditionalOptions{});
    t.factory = [](const CullerContext& c) -> std::unique_ptr<Culler> {
        return std::make_unique<ConditionalCuller>(conditionalOptionTable().read(c.options));
    };
    return t;
}

}  // namespace occsim
