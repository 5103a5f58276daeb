// Bittner, Wimmer, Piringer & Purgathofer, "Coherent Hierarchical Culling: Hardware Occlusion
// Queries Made Useful", Eurographics 2004: the algorithm of Figure "Pseudo-code of coherent
// hierarchical culling" with the optimisations of "Further Optimizations" (conservative
// visibility testing, approximate visibility). See chc_culler.h for the rules.
#include "culling/cullers/chc_culler.h"

#include "occsim/culling/declaration/culler_row.h"
#include "occsim/culling/declaration/option_table.h"
namespace occsim {

ChcCuller::ChcCuller(const ChcOptions& options) : options_(options) {}

void ChcCuller::reset(const BspTree& tree) {
    nodes_.reset(tree);
    traversal_queue_.clear();
    query_queue_.clear();
    query_head_ = 0;
}

void ChcCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    frame_ = frame.frame_index;
    view_ = prepareView(frame);
    nodes_.beginFrame(tree);
    traversal_queue_.clear();
    query_queue_.clear();
    query_head_ = 0;
    traversal_queue_.push(tree, {tree.root(), false}, frame.view.eye);

    while (!traversal_queue_.empty() || query_head_ < query_queue_.size()) {
        // PART 1: finished queries. The oldest result is waited for only when there is nothing
        // left to traverse; results become ready in issue order, so only the oldest is checked.
        while (query_head_ < query_queue_.size() &&
               (traversal_queue_.empty() || device.isQueryReady(query_queue_[query_head_].id))) {
            const PendingQuery query = query_queue_[query_head_++];
            handleResult(tree, frame, query, device.takeAnswer(query.id), device);
        }
        // PART 2: one step of the front-to-back traversal.
        if (!traversal_queue_.empty()) visitNode(tree, frame, traversal_queue_.pop(), device);
    }
}

void ChcCuller::visitNode(const BspTree& tree, const CullFrame& frame, NodeVisit visit,
                          RenderDevice& device) {
    switch (nodes_.visit(tree, view_, visit)) {
        case CoherentClassification::Visit::Culled:
            recordDecision(view_.decisions, QueryTag::node(visit.node),
                           decisionOf(DecisionKind::FrustumCulled));
            return;
        case CoherentClassification::Visit::NearPlane:
            traverseNode(tree, frame, visit, device, decisionOf(DecisionKind::DrawnNearPlane));
            return;
        case CoherentClassification::Visit::PreviouslyInvisible:
            issue(device, std::span<const Aabb>(&tree.bounds(visit.node), 1), visit,
                  QueryPurpose::Invisible);
            return;
        case CoherentClassification::Visit::PreviouslyVisible:
            break;
    }
    const bool inside = visit.inside_frustum;
    const Aabb& box = tree.bounds(visit.node);

    // Previously visible: render without waiting. Its own geometry (a leaf's objects, or an
    // inner node's straddlers) is queried for the next frame unless it is still assumed visible.
    const bool query_due = frame_ >= nodes_[visit.node].next_query;
    if (tree.node(visit.node).isLeaf()) {
        if (query_due) {
            issue(device, std::span<const Aabb>(&box, 1), visit, QueryPurpose::Visible);
        } else {
            nodes_.pullUp(tree, visit.node);
        }
    } else {
        boxes_.clear();
        if (appendOwnObjectBoxes(tree, visit.node, view_.frustum, inside, boxes_) > 0) {
            if (query_due) {
                issue(device, boxes_, visit, QueryPurpose::Own);
            } else {
                nodes_.pullUp(tree, visit.node);
            }
        }
    }
    traverseNode(tree, frame, visit, device,
                 nodes_.previouslyVisible(visit.node, query_due, frame_));
}

void ChcCuller::handleResult(const BspTree& tree, const CullFrame& frame, const PendingQuery& query,
                             const QueryAnswer& answer, RenderDevice& device) {
    if (!answer.visible) {  // stays invisible
        // Only a node that was waited for is decided by the answer; the others were drawn.
        if (query.purpose == QueryPurpose::Invisible) {
            recordDecision(view_.decisions, QueryTag::node(query.node),
                           answeredDecision(frame_, answer));
        }
        return;
    }
    // Found visible: assumed visible (no query on its geometry) for the next t_av frames.
    nodes_[query.node].next_query = frame_ + 1 + options_.visible_frames_skip;
    nodes_[query.node].found_visible = frame_;
    nodes_.pullUp(tree, query.node);
    // Only a node that was waited for is traversed now; the others were rendered at their visit.
    if (query.purpose == QueryPurpose::Invisible) {
        traverseNode(tree, frame, {query.node, query.inside_frustum}, device,
                     answeredDecision(frame_, answer));
    }
}

void ChcCuller::traverseNode(const BspTree& tree, const CullFrame& frame, const NodeVisit& visit,
                             RenderDevice& device, const Decision& why) {
    drawNodeObjects(tree, visit.node, view_, visit.inside_frustum, device, why);
    traversal_queue_.pushChildren(tree, visit.node, frame.view.eye, visit.inside_frustum);
}

void ChcCuller::issue(RenderDevice& device, std::span<const Aabb> boxes, const NodeVisit& visit,
                      QueryPurpose purpose) {
    const QueryTag subject = purpose == QueryPurpose::Own ? QueryTag::nodeObjects(visit.node)
                                                          : QueryTag::node(visit.node);
    const QueryId id = device.issueQuery(boxes, std::span<const QueryTag>(&subject, 1));
    query_queue_.push_back({id, visit.node, visit.inside_frustum, purpose});
}

// --- Registration -------------------------------------------------------------------------------

namespace {

const OptionTable<ChcOptions>& chcOptionTable() {
    static const OptionTable<ChcOptions> table = {
        integerOption(OCCSIM_OPTION_MEMBER(ChcOptions, visible_frames_skip), "frames", 0, 1000000,
                      "t_av: a leaf found visible is assumed visible, with no query, for this many "
                      "frames; 0 = the basic algorithm"),
    };
    return table;
}

}  // namespace

CullerRow chcRegistration() {
    CullerRow t;
    t.name = "chc";
    t.summary = "coherent hierarchical culling (Bittner et al. 2004)";
    t.issues_queries = true;
    t.options = chcOptionTable().descriptor(ChcOptions{});
    t.factory = [](const CullerContext& c) -> std::unique_ptr<Culler> {
        return std::make_unique<ChcCuller>(chcOptionTable().read(c.options));
    };
    return t;
}

}  // namespace occsim
