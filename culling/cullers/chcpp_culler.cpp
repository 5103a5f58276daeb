// Mattausch, Bittner & Wimmer, "CHC++: Coherent Hierarchical Culling Revisited", Eurographics
// 2008: queues for batching (i-queue, v-queue, render queue, section 4), multiqueries (5.1),
// randomised sampling of visible nodes (5.2) and tight bounds from the hierarchy (6). See
// chcpp_culler.h for the rules.
#include "culling/cullers/chcpp_culler.h"

#include <algorithm>
#include <cmath>

#include "occsim/culling/declaration/culler_row.h"
#include "occsim/culling/declaration/option_table.h"
#include "occsim/culling/geometry/random.h"

namespace occsim {

namespace {

constexpr uint32_t kMaxInvisibleFrames = 1000;  // p(i) has long converged by then

// CHC++'s fit of the probability that a node invisible for i frames stays invisible.
double keepInvisibleProbability(uint32_t invisible_frames) {
    return 0.99 - 0.7 * std::exp(-static_cast<double>(invisible_frames));
}

}  // namespace

ChcppCuller::ChcppCuller(const ChcppOptions& options) : options_(options) {}

void ChcppCuller::clearQueues() {
    traversal_queue_.clear();
    query_queue_.clear();
    query_head_ = 0;
    i_queue_.clear();
    v_queue_.clear();
    v_head_ = 0;
    render_queue_.clear();
    multi_nodes_.clear();
}

void ChcppCuller::reset(const BspTree& tree) {
    nodes_.reset(tree);
    clearQueues();
}

void ChcppCuller::cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) {
    frame_ = frame.frame_index;
    view_ = prepareView(frame);
    nodes_.beginFrame(tree);
    stats_ = {};
    device_state_ = DeviceState::None;
    clearQueues();
    traversal_queue_.push(tree, {tree.root(), false}, frame.view.eye);

    for (;;) {
        // Finished queries first. When there is nothing to traverse and the oldest result is not
        // there yet, do useful work before waiting: the pending batch (which renders the render
        // queue first), else the render queue, else one v-queue query; block only when none of
        // them is left.
        while (query_head_ < query_queue_.size()) {
            const PendingQuery& front = query_queue_[query_head_];
            if (!device.isQueryReady(front.id)) {
                if (!traversal_queue_.empty()) break;
                if (!i_queue_.empty()) {
                    issueBatch(tree, device);
                    continue;
                }
                if (!render_queue_.empty()) {
                    flushRenderQueue(tree, device);
                    continue;
                }
                if (v_head_ < v_queue_.size()) {
                    ++stats_.fill_queries;
                    issueVisibleQuery(tree, device);
                    continue;
                }
            }
            const PendingQuery query = query_queue_[query_head_++];
            handleResult(tree, frame, query, device.takeAnswer(query.id), device);
        }

        if (!traversal_queue_.empty()) {
            visitNode(tree, frame, traversal_queue_.pop());
            if (i_queue_.size() >= options_.batch_size) issueBatch(tree, device);
        } else if (!i_queue_.empty()) {
            issueBatch(tree, device);
        } else if (v_head_ < v_queue_.size()) {
            // Nothing left to find: the remaining v-queue queries, after the remaining geometry.
            flushRenderQueue(tree, device);
            while (v_head_ < v_queue_.size()) issueVisibleQuery(tree, device);
        } else if (query_head_ == query_queue_.size()) {
            break;
        }
    }
    flushRenderQueue(tree, device);
}

void ChcppCuller::visitNode(const BspTree& tree, const CullFrame& frame, NodeVisit visit) {
    switch (nodes_.visit(tree, view_, visit)) {
        case CoherentClassification::Visit::Culled:
            recordDecision(view_.decisions, QueryTag::node(visit.node),
                           decisionOf(DecisionKind::FrustumCulled));
            return;
        case CoherentClassification::Visit::NearPlane:
            traverseNode(tree, frame, visit, decisionOf(DecisionKind::DrawnNearPlane));
            return;
        case CoherentClassification::Visit::PreviouslyInvisible:
            i_queue_.push_back({visit.node, visit.inside_frustum, false, QueryPurpose::Invisible});
            return;
        case CoherentClassification::Visit::PreviouslyVisible:
            break;
    }
    const bool inside = visit.inside_frustum;
    CoherentClassification::NodeState& s = nodes_[visit.node];
    s.invisible_frames = 0;
    const bool query_due = frame_ >= s.next_query;
    bool has_geometry = true;
    QueryPurpose purpose = QueryPurpose::Visible;
    if (!tree.node(visit.node).isLeaf()) {
        boxes_.clear();
        has_geometry = appendOwnObjectBoxes(tree, visit.node, view_.frustum, inside, boxes_) > 0;
        purpose = QueryPurpose::Own;
    }
    if (has_geometry) {
        if (query_due) {
            v_queue_.push_back({visit.node, inside, false, purpose});
        } else {
            nodes_.pullUp(tree, visit.node);  // still assumed visible
        }
    }
    traverseNode(tree, frame, visit, nodes_.previouslyVisible(visit.node, query_due, frame_));
}

void ChcppCuller::handleResult(const BspTree& tree, const CullFrame& frame,
                               const PendingQuery& query, const QueryAnswer& answer,
                               RenderDevice& device) {
    const bool visible = answer.visible;
    switch (query.purpose) {
        case QueryPurpose::Multi:
            if (visible) {
                // Coherence broke somewhere in the group: query each node on its own.
                ++stats_.failed_multiqueries;
                for (uint32_t i = 0; i < query.group_size; ++i) {
                    QueuedNode n = multi_nodes_[query.group_begin + i];
                    n.single = true;
                    i_queue_.push_back(n);
                }
                if (i_queue_.size() >= options_.batch_size) issueBatch(tree, device);
            } else {
                Decision why = answeredDecision(frame_, answer);
                why.flags |= kDecisionMultiquery;
                for (uint32_t i = 0; i < query.group_size; ++i) {
                    const uint32_t node = multi_nodes_[query.group_begin + i].node;
                    nodes_.markInvisible(node, kMaxInvisibleFrames);
                    recordDecision(view_.decisions, QueryTag::node(node), why);
                }
            }
            break;
        case QueryPurpose::Invisible:
            if (visible) {
                CoherentClassification::NodeState& s = nodes_[query.node];
                s.invisible_frames = 0;
                s.next_query = firstRetestFrame(query.node);
                s.found_visible = frame_;
                nodes_.pullUp(tree, query.node);
                traverseNode(tree, frame, {query.node, query.inside_frustum},
                             answeredDecision(frame_, answer));
            } else {
                nodes_.markInvisible(query.node, kMaxInvisibleFrames);
                recordDecision(view_.decisions, QueryTag::node(query.node),
                               answeredDecision(frame_, answer));
            }
            break;
        case QueryPurpose::Visible:
        case QueryPurpose::Own:
            if (visible) {
                // Visible at its previous test too: the regular interval.
                nodes_[query.node].next_query = frame_ + 1 + options_.visible_frames_skip;
                nodes_[query.node].found_visible = frame_;
                nodes_.pullUp(tree, query.node);
            }
            break;
    }
}

void ChcppCuller::traverseNode(const BspTree& tree, const CullFrame& frame, const NodeVisit& visit,
                               const Decision& why) {
    if (tree.firstObject(visit.node) != BspTree::kNone) {
        // Decided now, drawn when the render queue is flushed (which records the frustum's
        // decisions on its objects after this one).
        recordDecision(view_.decisions, QueryTag::nodeObjects(visit.node), why);
        render_queue_.push_back(visit);
    }
    traversal_queue_.pushChildren(tree, visit.node, frame.view.eye, visit.inside_frustum);
}

uint64_t ChcppCuller::firstRetestFrame(uint32_t node) const {
    const uint32_t n_av = options_.visible_frames_skip;
    if (n_av == 0) return frame_ + 1;
    const uint64_t r =
        splitMix64(options_.seed ^ splitMix64(uint64_t{node} ^ splitMix64(frame_))) % n_av;
    return frame_ + 1 + r;
}

void ChcppCuller::issueBatch(const BspTree& tree, RenderDevice& device) {
    // Render what is waiting first, so the batch tests against as much depth as possible.
    flushRenderQueue(tree, device);
    ++stats_.query_batches;

    order_.clear();
    for (uint32_t i = 0; i < i_queue_.size(); ++i) order_.push_back(i);
    // Nodes whose multiquery failed come first, alone; the rest by how long they have been
    // invisible, longest first, so that groups gather nodes with similar histories; ties keep
    // the traversal order (std::sort with a total order: stable_sort would allocate).
    std::sort(order_.begin(), order_.end(), [this](uint32_t a, uint32_t b) {
        const QueuedNode& na = i_queue_[a];
        const QueuedNode& nb = i_queue_[b];
        if (na.single != nb.single) return na.single;
        const uint32_t ia = nodes_[na.node].invisible_frames;
        const uint32_t ib = nodes_[nb.node].invisible_frames;
        if (ia != ib) return ia > ib;
        return a < b;
    });

    size_t i = 0;
    while (i < order_.size()) {
        const QueuedNode& first = i_queue_[order_[i]];
        size_t end = i + 1;
        if (options_.multiqueries && !first.single) {
            // Grow the group while the expected number of nodes settled per query grows.
            double keep = keepInvisibleProbability(nodes_[first.node].invisible_frames);
            double best = 1.0;
            while (end < order_.size() && !i_queue_[order_[end]].single) {
                const uint32_t node = i_queue_[order_[end]].node;
                const double next_keep =
                    keep * keepInvisibleProbability(nodes_[node].invisible_frames);
                const double size = static_cast<double>(end - i + 1);
                const double value = size / (1.0 + (1.0 - next_keep) * size);
                if (value <= best) break;
                best = value;
                keep = next_keep;
                ++end;
            }
        }
        if (end - i == 1) {
            issueSingle(tree, device, first);
        } else {
            const auto start = static_cast<uint32_t>(multi_nodes_.size());
            boxes_.clear();
            tags_.clear();
            for (size_t k = i; k < end; ++k) {
                multi_nodes_.push_back(i_queue_[order_[k]]);
                appendQueryBoxes(tree, i_queue_[order_[k]].node, options_.tight_bounds_depth);
                tags_.push_back(QueryTag::node(i_queue_[order_[k]].node));
            }
            enterState(DeviceState::Query);
            query_queue_.push_back({device.issueQuery(boxes_, tags_), BspTree::kNone, start,
                                    static_cast<uint32_t>(end - i), false, QueryPurpose::Multi});
            ++stats_.multiqueries;
            stats_.multiquery_nodes += static_cast<uint32_t>(end - i);
        }
        i = end;
    }
    i_queue_.clear();
}

void ChcppCuller::issueVisibleQuery(const BspTree& tree, RenderDevice& device) {
    const QueuedNode n = v_queue_[v_head_++];
    ++stats_.visible_queries;
    boxes_.clear();
    if (n.purpose == QueryPurpose::Own) {
        appendOwnObjectBoxes(tree, n.node, view_.frustum, n.inside_frustum, boxes_);
    } else {
        appendQueryBoxes(tree, n.node, 0);
    }
    enterState(DeviceState::Query);
    const QueryTag subject =
        n.purpose == QueryPurpose::Own ? QueryTag::nodeObjects(n.node) : QueryTag::node(n.node);
    const QueryId id = device.issueQuery(boxes_, std::span<const QueryTag>(&subject, 1));
    query_queue_.push_back({id, n.node, 0, 0, n.inside_frustum, n.purpose});
}

void ChcppCuller::issueSingle(const BspTree& tree, RenderDevice& device, const QueuedNode& n) {
    boxes_.clear();
    appendQueryBoxes(tree, n.node, options_.tight_bounds_depth);
    enterState(DeviceState::Query);
    const QueryTag subject = QueryTag::node(n.node);
    const QueryId id = device.issueQuery(boxes_, std::span<const QueryTag>(&subject, 1));
    query_queue_.push_back({id, n.node, 0, 0, n.inside_frustum, QueryPurpose::Invisible});
}

void ChcppCuller::flushRenderQueue(const BspTree& tree, RenderDevice& device) {
    if (render_queue_.empty()) return;
    enterState(DeviceState::Render);
    for (const NodeVisit& visit : render_queue_) {
        forEachObjectInFrustum(tree, visit.node, view_, visit.inside_frustum,
                               [&device](uint32_t o) { device.drawObject(o); });
    }
    render_queue_.clear();
}

// The boxes a query on `node` rasterises: its own bounds, or with tight bounds the bounds of its
// descendants `depth` levels down, plus one box around the straddlers of each inner node on the
// way (they belong to the subtree but to none of those descendants).
void ChcppCuller::appendQueryBoxes(const BspTree& tree, uint32_t node, uint32_t depth) {
    const BspNode& n = tree.node(node);
    if (isEmpty(n.bounds)) return;
    if (depth == 0 || n.isLeaf()) {
        boxes_.push_back(n.bounds);
        return;
    }
    Aabb own;
    for (uint32_t o = tree.firstObject(node); o != BspTree::kNone; o = tree.nextObject(o)) {
        extend(own, tree.objectBox(o));
    }
    if (!isEmpty(own)) boxes_.push_back(own);
    appendQueryBoxes(tree, n.child[0], depth - 1);
    appendQueryBoxes(tree, n.child[1], depth - 1);
}

void ChcppCuller::enterState(DeviceState state) {
    if (device_state_ != DeviceState::None && device_state_ != state) ++stats_.state_changes;
    device_state_ = state;
}

// --- Registration -------------------------------------------------------------------------------

namespace {

const OptionTable<ChcppOptions>& chcppOptionTable() {
    using O = ChcppOptions;
    static const OptionTable<O> table = {
        integerOption(OCCSIM_OPTION_MEMBER(O, visible_frames_skip), "frames", 0, 1000000,
                      "n_av: frames a node found visible is assumed visible before it is tested "
                      "again"),
        integerOption(OCCSIM_OPTION_MEMBER(O, batch_size), "nodes", 1, 4294967295.0,
                      "previously invisible nodes per batch of queries"),
        booleanOption(OCCSIM_OPTION_MEMBER(O, multiqueries),
                      "group previously invisible nodes into multiqueries; false: one query per "
                      "node"),
        integerOption(OCCSIM_OPTION_MEMBER(O, tight_bounds_depth), "tree levels", 0, 6,
                      "query a previously invisible node with its descendants' boxes this many "
                      "levels down; 0 = its own box"),
        integerOption(OCCSIM_OPTION_MEMBER(O, seed), "", 0, kMaxExactInteger,
                      "seeds the randomised first re-test of nodes that turned visible"),
    };
    return table;
}

}  // namespace

CullerRow chcppRegistration() {
    CullerRow t;
    t.name = "chc++";
    t.summary = "CHC++ (Mattausch et al. 2008)";
    t.issues_queries = true;
    t.options = chcppOptionTable().descriptor(ChcppOptions{});
    t.factory = [](const CullerContext& c) -> std::unique_ptr<Culler> {
        return std::make_unique<ChcppCuller>(chcppOptionTable().read(c.options));
    };
    return t;
}

}  // namespace occsim
