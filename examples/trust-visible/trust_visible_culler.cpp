// The culler and its plugin registration: the one file an out-of-tree culler needs besides its
// header, and the entry point (OCCSIM_PLUGIN) that `occsim --plugin` loads.
#include "trust_visible_culler.h"

namespace example {

void TrustVisibleCuller::cullAndRender(const occsim::BspTree& tree, const occsim::CullFrame& frame,
                                       occsim::RenderDevice& device) {
    last_visible_s_.sync(tree);  // the tree adapts as objects move: keep the state of kept nodes
    const occsim::PreparedView view = occsim::prepareView(frame.view);
    occsim::traverseFrontToBack(tree, view, stack_, [&](const occsim::NodeVisit& visit) {
        const occsim::Aabb& box = tree.bounds(visit.node);
        Seen& seen = last_visible_s_[visit.node];
        const bool trusted = frame.time_s - seen.time_s < trust_s_;
        // A box the near plane may cut is never queried: a clipped query could report nothing.
        if (!trusted && !occsim::nearPlaneTouchesBox(box, view.eye, view.near_radius)) {
            const occsim::QueryId id = device.issueQuery(box, occsim::QueryTag::node(visit.node));
            if (!device.takeAnswer(id).visible) return false;  // occluded: skip the subtree
            seen.time_s = frame.time_s;
        }
        occsim::drawNodeObjects(tree, visit.node, view.frustum, visit.inside_frustum, device);
        return true;
    });
}

}  // namespace example

namespace {

std::unique_ptr<occsim::Culler> makeTrustVisible(const occsim::CullerContext& context) {
    return std::make_unique<example::TrustVisibleCuller>(context.options.number("trust"));
}

void registerCullers(occsim::PluginRegistrar& registrar) {
    occsim::CullerRow t;
    t.name = "trust-visible";
    t.summary =
        "stop-and-wait queries; a node found visible is trusted for a while (example plugin)";
    t.conservative = true;
    t.issues_queries = true;
    // culling["trust-visible"].trust in a scenario; occtune --algo trust-visible tunes it.
    t.options = {occsim::tunable(occsim::numberOption("trust", "s", 0.0, 60.0, 0.5,
                                                      "a node found visible is drawn without a "
                                                      "query for this long"),
                                 0.0, 2.0)};
    t.factory = makeTrustVisible;
    registrar.add(std::move(t));
}

}  // namespace

OCCSIM_PLUGIN("trust-visible example", registerCullers)
