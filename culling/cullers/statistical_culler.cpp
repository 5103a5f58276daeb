// Kovalčík & Sochor, "Occlusion Culling with Statistically Optimized Occlusion Queries",
// WSCG 2005 short papers, section 3 (the two-queue traversal and the optimised CalcNodeAction),
// with the improvements of StatisticalOptions (docs/statistical.md), each off by default.
#include "culling/cullers/statistical_culler.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace occsim {
namespace {

// Parallax re-query (requery_parallax): a node closer than this counts as this far, so a node
// at the eye does not divide by zero.
constexpr double kMinParallaxDistanceM = 1e-3;
// Weight of one answer in a PriorResult's running occlusion estimate (exponential moving averages
// over answers: about the last 16 answers of that kind count).
constexpr double kRateWeight = 1.0 / 16.0;
// The fallback looks at the share of visible answers only once the window holds at least this
// many answers per frame on average, so that a handful of answers decides nothing.
constexpr uint32_t kFallbackMinAnswersPerFrame = 2;

// distance_order's rank: the squared distance from the eye to a box. Non-negative floats order
// as their bit patterns do, so the rank stays an integer and the heap is the same.
uint32_t distanceRank(const Aabb& box, glm::vec3 eye) {
    const float d2 = distanceSquared(box, eye);
    return std::bit_cast<uint32_t>(d2 >= 0.0f ? d2 : 0.0f);  // a NaN box: nearest, never lost
}

// Orders the main queue's heap so that the lowest rank comes out first.
struct LaterRank {
    template <class E>
    bool operator()(const E& a, const E& b) const {
        return a.rank > b.rank;
    }
};

}  // namespace

RequeryInterval requeryInterval(const StatisticalOptions& options, const NodeStatistics& stats,
                                NodeMotion motion) {
    const uint32_t mask =
        options.history_length >= 32 ? ~0u : ((1u << options.history_length) - 1u);
    RequeryInterval r;
    r.visible_results = std::popcount(stats.history & mask);
    const double decay = options.decay_a - std::pow(options.decay_b, r.visible_results);
    // The interval runs from the last query, or from the last time the cost model put the query
    // off (improvement 3), whichever is later.
    if (options.requeriesByDistance()) {
        r.distance = true;
        r.since = std::max(stats.travel_at_query_m, stats.deferred_travel_m);
        if (options.requery_distance_m > 0.0) {
            r.interval = options.requery_distance_m * decay;
        } else {
            const double distance = std::max(motion.distance_m, kMinParallaxDistanceM);
            r.interval = options.requery_parallax * decay * distance;
        }
        return r;
    }
    r.since = std::max(stats.last_query_time_s, stats.deferred_time_s);
    r.interval = options.base_time_s * decay;
    return r;
}

double requeryHorizonFrames(const StatisticalOptions& options, const RequeryInterval& r,
                            double step_m, double dt_s) {
    if (!(dt_s > 0.0)) return 1.0;
    const double most = std::max(1.0, options.max_statistics_age_s / dt_s);
    // The rate the interval is spent at: metres of travel per frame, or seconds per frame. A
    // subject that did not advance (camera and movers still) keeps its answer until its
    // statistics are too old.
    const double per_frame = r.distance ? step_m : dt_s;
    if (!(per_frame > 0.0)) return most;
    return std::clamp(r.interval / per_frame, 1.0, most);
}

NodeAction decideNodeAction(const StatisticalOptions& options, const NodeStatistics& stats,
                            bool near_plane_touches_box, double now_s, NodeMotion motion) {
    if (near_plane_touches_box) return NodeAction::Render;
    if (stats.results == 0) return NodeAction::Query;
    if (now_s - stats.last_query_time_s > options.max_statistics_age_s) return NodeAction::Query;
    if ((stats.history & 1u) == 0) return NodeAction::Query;  // last result: occluded
    const RequeryInterval r = requeryInterval(options, stats, motion);
    if (r.distance) {
        const double travelled = motion.travel_m - r.since;
        return travelled > r.interval ? NodeAction::Query : NodeAction::Render;
    }
    const double not_query_time = r.since + r.interval;
    return now_s > not_query_time ? NodeAction::Query : NodeAction::Render;
}

void recordQueryResult(const StatisticalOptions& options, NodeStatistics& stats, bool visible,
                       double now_s, double travel_m) {
    stats.history = (stats.history << 1) | (visible ? 1u : 0u);
    if (stats.results < options.history_length) ++stats.results;
    stats.last_query_time_s = now_s;
    stats.travel_at_query_m = travel_m;
}

PriorResult priorResultOf(const NodeStatistics& stats) {
    if (stats.results == 0) return PriorResult::Fresh;
    return (stats.history & 1u) ? PriorResult::LastVisible : PriorResult::LastOccluded;
}

bool statisticsUsable(const StatisticalOptions& options, const NodeStatistics& stats,
                      double now_s) {
    return stats.results > 0 && now_s - stats.last_query_time_s <= options.max_statistics_age_s;
}

void OcclusionEstimate::add(bool was_occluded) {
    occluded += kRateWeight * ((was_occluded ? 1.0 : 0.0) - occluded);
}

bool queryPays(const CostModel& costs, double draw_ms, uint32_t query_boxes,
               double occlusion_rate) {
    return occlusion_rate * draw_ms > static_cast<double>(query_boxes) * costs.query_box_ms;
}

StatisticalCuller::StatisticalCuller(const StatisticalOptions& options, const CostModel& costs)
    : options_(options), costs_(costs) {}

void StatisticalCuller::reset(const BspTree& tree) {
    stats_.reset(tree);
    own_stats_.reset(tree);
    motion_.reset(tree);
    structure_known_ = false;
    heap_.clear();
    pending_.clear();
    pending_head_ = 0;
    in_flight_weight_ = 0.0;
    waited_weight_ = 0.0;
    last_waited_weight_ = 0.0;
    updates_.clear();  // ids still in flight on an earlier device are that device's to forget
    updates_head_ = 0;
    // A frame issues at most one query per subject (a node, its virtual leaf, an object), and
    // update answers are all taken by the start of the next frame: with this much room, a frame
    // that re-queries more than any before it allocates nothing (the tree adapts, so with slack).
    const size_t subjects = 2 * (2 * size_t{tree.nodeCount()} + tree.objectCount());
    updates_.reserve(subjects);
    pending_.reserve(subjects);
    last_center_.clear();
    have_last_frame_ = false;
    camera_path_m_ = 0.0;
    camera_step_m_ = 0.0;
    last_time_s_ = std::numeric_limits<double>::quiet_NaN();  // no frame yet: dt_s_ is NaN
    dt_s_ = 0.0;
    estimates_.fill(OcclusionEstimate{});
    object_stats_.assign(tree.objectCount(), NodeStatistics{});
    object_motion_m_.assign(tree.objectCount(), 0.0);
    object_step_m_.assign(tree.objectCount(), 0.0f);
    window_answers_.assign(options_.fallback_window_frames, 0);
    window_visible_.assign(options_.fallback_window_frames, 0);
    window_next_ = 0;
    window_frames_ = 0;
    frustum_only_ = false;
    frustum_only_until_s_ = 0.0;
    counters_ = {};
}

// Depth-first order of the nodes, and how many ranks each subtree spans: the node, the virtual
// leaf of its own objects (inner nodes), and both children's subtrees. Only the structure
// matters, so this runs again only when the tree's structure changed. It walks the tree rather
// than scanning indices, so it assumes nothing about how a changing tree numbers its nodes.
void StatisticalCuller::syncStructure(const BspTree& tree) {
    if (structure_known_ && structure_version_ == tree.structureVersion() &&
        subtree_ranks_.size() == tree.nodeCount()) {
        return;
    }
    order_.clear();
    scratch_stack_.clear();
    scratch_stack_.push_back(tree.root());
    while (!scratch_stack_.empty()) {
        const uint32_t n = scratch_stack_.back();
        scratch_stack_.pop_back();
        order_.push_back(n);
        const BspNode& node = tree.node(n);
        if (!node.isLeaf()) {
            scratch_stack_.push_back(node.child[1]);
            scratch_stack_.push_back(node.child[0]);
        }
    }
    subtree_ranks_.assign(tree.nodeCount(), 0);
    for (auto it = order_.rbegin(); it != order_.rend(); ++it) {
        const BspNode& node = tree.node(*it);
        subtree_ranks_[*it] =
            node.isLeaf() ? 1 : 2 + subtree_ranks_[node.child[0]] + subtree_ranks_[node.child[1]];
    }
    structure_version_ = tree.structureVersion();
    structure_known_ = true;
}

void StatisticalCuller::prepareFrame(const BspTree& tree, const CullFrame& frame) {
    stats_.sync(tree);
    own_stats_.sync(tree);
    motion_.sync(tree);
    syncStructure(tree);
    dt_s_ = frame.time_s - last_time_s_;
    last_time_s_ = frame.time_s;

    // Cost model: what drawing each subtree would cost, bottom-up over the tree as it is now.
    costs_active_ = options_.cost_model && costs_.known() &&
                    frame.object_triangles.size() == tree.objectCount();
    if (costs_active_) {
        subtree_draw_ms_.resize(tree.nodeCount());
        for (auto it = order_.rbegin(); it != order_.rend(); ++it) {
            const uint32_t n = *it;
            double ms = 0.0;
            for (uint32_t o = tree.firstObject(n); o != BspTree::kNone; o = tree.nextObject(o)) {
                ms += costs_.drawMs(frame.object_triangles[o]);
            }
            const BspNode& node = tree.node(n);
            if (!node.isLeaf())
                ms += subtree_draw_ms_[node.child[0]] + subtree_draw_ms_[node.child[1]];
            subtree_draw_ms_[n] = ms;
        }
    }

    // Distance rules: the camera's path, and per node the largest step any object below it took
    // this frame, summed over frames. Object centres stand for the movers (the culling layer
    // knows boxes, not movers); a static object's step is 0.
    if (options_.requeriesByDistance()) {
        const bool first = !have_last_frame_ || last_center_.size() != tree.objectCount();
        camera_step_m_ = 0.0;
        if (first) {
            last_center_.resize(tree.objectCount());
            for (uint32_t o = 0; o < tree.objectCount(); ++o)
                last_center_[o] = center(tree.objectBox(o));
        } else {
            camera_step_m_ = glm::length(frame.view.eye - last_eye_);
            camera_path_m_ += camera_step_m_;
        }
        last_eye_ = frame.view.eye;
        have_last_frame_ = true;
        step_m_.resize(tree.nodeCount());
        own_step_m_.resize(tree.nodeCount());
        for (auto it = order_.rbegin(); it != order_.rend(); ++it) {
            const uint32_t n = *it;
            float own = 0.0f;
            for (uint32_t o = tree.firstObject(n); o != BspTree::kNone; o = tree.nextObject(o)) {
                const glm::vec3 c = center(tree.objectBox(o));
                const float step = glm::length(c - last_center_[o]);
                last_center_[o] = c;
                object_step_m_[o] = 0.0f;
                if (!(step <= 1e30f)) continue;  // a non-finite box adds nothing
                object_step_m_[o] = step;
                own = std::max(own, step);
                object_motion_m_[o] += step;
            }
            float subtree = own;
            const BspNode& node = tree.node(n);
            if (!node.isLeaf())
                subtree = std::max({subtree, step_m_[node.child[0]], step_m_[node.child[1]]});
            step_m_[n] = subtree;
            own_step_m_[n] = own;
            motion_[n].own_m += own;
            motion_[n].subtree_m += subtree;
        }
    }
}

double StatisticalCuller::stepOf(const Entry& e) const {
    // Only the distance rules count steps (prepareFrame fills them for those only).
    if (!options_.requeriesByDistance()) return 0.0;
    switch (e.subject) {
        case Subject::Node:
            return camera_step_m_ + step_m_[e.index];
        case Subject::NodeObjects:
            return camera_step_m_ + own_step_m_[e.index];
        case Subject::Object:
            return camera_step_m_ + object_step_m_[e.index];
    }
    return camera_step_m_;
}

double StatisticalCuller::travelOf(const Entry& e) const {
    switch (e.subject) {
        case Subject::Node:
            return camera_path_m_ + motion_[e.index].subtree_m;
        case Subject::NodeObjects:
            return camera_path_m_ + motion_[e.index].own_m;
        case Subject::Object:
            return camera_path_m_ + object_motion_m_[e.index];
    }
    return camera_path_m_;
}

NodeStatistics& StatisticalCuller::statsOf(const Entry& e) {
    switch (e.subject) {
        case Subject::Node:
            return stats_[e.index];
        case Subject::NodeObjects:
            return own_stats_[e.index];
        case Subject::Object:
            return object_stats_[e.index];
    }
    return stats_[e.index];
}

void StatisticalCuller::push(const Entry& entry) {
    heap_.push_back(entry);
    std::push_heap(heap_.begin(), heap_.end(), LaterRank{});
}

StatisticalCuller::Entry StatisticalCuller::pop() {
    std::pop_heap(heap_.begin(), heap_.end(), LaterRank{});
    const Entry e = heap_.back();
    heap_.pop_back();
    return e;
}

// A rendered node: its own objects are drawn (or, with virtual leaves, queued to be decided on
// their own statistics, between the nearer and the farther child), and its children take its
// place in the queue, nearer child first. Empty children are left out (the paper's SKIP).
void StatisticalCuller::renderNode(const BspTree& tree, const CullFrame& frame, const Entry& entry,
                                   RenderDevice& device, const Decision& why) {
    const BspNode& n = tree.node(entry.index);
    if (n.isLeaf()) {
        renderObjects(tree, frame, entry.index, entry.inside_frustum, device, why);
        return;
    }
    const bool eye_below = frame.view.eye[n.axis] < n.split;
    const uint32_t near_child = n.child[eye_below ? 0 : 1];
    const uint32_t far_child = n.child[eye_below ? 1 : 0];
    // Ranks: the node's place in the depth-first order (itself, its virtual leaf after the nearer
    // child's subtree, then the farther child), or with distance_order the distance from the eye
    // to each subject's bounds (a virtual leaf: its node's bounds, so before its children).
    const uint32_t near_size = subtree_ranks_[near_child];
    uint32_t own_rank = entry.rank + 1 + near_size;
    uint32_t near_rank = entry.rank + 1;
    uint32_t far_rank = own_rank + 1;
    if (options_.distance_order) {
        const glm::vec3 eye = frame.view.eye;
        own_rank = distanceRank(tree.bounds(entry.index), eye);
        near_rank = distanceRank(tree.bounds(near_child), eye);
        far_rank = distanceRank(tree.bounds(far_child), eye);
    }
    if (options_.virtual_leaves) {
        if (n.object_count > 0) {
            push({own_rank, entry.index, Subject::NodeObjects, entry.inside_frustum});
        }
    } else {
        // Without virtual leaves, objects in inner nodes have no decisions of their own.
        drawNodeObjects(tree, entry.index, view_, entry.inside_frustum, device, why);
    }
    if (!isEmpty(tree.bounds(near_child))) {
        push({near_rank, near_child, Subject::Node, entry.inside_frustum});
    }
    if (!isEmpty(tree.bounds(far_child))) {
        push({far_rank, far_child, Subject::Node, entry.inside_frustum});
    }
}

NodeAction StatisticalCuller::decide(const CullFrame& frame, NodeStatistics& stats, const Aabb& box,
                                     const Entry& subject, double draw_ms, uint32_t query_boxes,
                                     QueryContext* context, Decision* why) {
    const bool object_query = subject.subject == Subject::Object;
    const double travel_m = travelOf(subject);
    const CullView& view = frame.view;
    const bool near = nearPlaneTouchesBox(box, view.eye, view.near_radius);
    const NodeMotion motion{travel_m, glm::length(center(box) - view.eye)};
    const NodeAction action = decideNodeAction(options_, stats, near, frame.time_s, motion);
    context->prior = priorResultOf(stats);
    if (action == NodeAction::Render) {
        ++counters_.renders_without_query;
        if (near) {
            *why = decisionOf(DecisionKind::DrawnNearPlane);
        } else if (view_.decisions) {
            *why = statisticsDecision(stats, motion);
        }
        return action;
    }
    if (!costs_active_) return NodeAction::Query;
    *why = decisionOf(DecisionKind::DrawnOnCostModel);
    // Rule 1 (Guthe et al.): a subject cheaper to draw than to query is drawn without one,
    // statistics or not.
    if (!queryPays(costs_, draw_ms, query_boxes, 1.0)) {
        ++counters_.cost_model_renders;
        return NodeAction::Render;
    }
    // Rule 2: with usable statistics, the occlusion estimate of this kind of query must make it
    // pay. Without them the answer is worth more than one frame's saving (later decisions go on
    // it), so the query is issued.
    if (!statisticsUsable(options_, stats, frame.time_s)) return NodeAction::Query;
    OcclusionEstimate& estimate = estimates_[estimateIndex(context->prior, object_query)];
    // Improvement (10): a re-query of what was visible decides every frame until the next one.
    double saving_frames = 1.0;
    if (options_.requery_horizon && context->prior == PriorResult::LastVisible) {
        saving_frames = requeryHorizonFrames(options_, requeryInterval(options_, stats, motion),
                                             stepOf(subject), dt_s_);
    }
    if (queryPays(costs_, draw_ms * saving_frames, query_boxes, estimate.occluded)) {
        return NodeAction::Query;
    }
    if (++estimate.vetoes >= OcclusionEstimate::kExploreEvery) {
        estimate.vetoes = 0;  // asked anyway, so that the estimate stays measured
        return NodeAction::Query;
    }
    // Put off: CalcNodeAction's interval starts again from now, as if the node had just been
    // found visible, but the history and the age of the statistics stay what they were.
    stats.deferred_time_s = frame.time_s;
    stats.deferred_travel_m = travel_m;
    ++counters_.cost_model_renders;
    return NodeAction::Render;
}

Decision StatisticalCuller::statisticsDecision(const NodeStatistics& stats,
                                               const NodeMotion& motion) const {
    const RequeryInterval r = requeryInterval(options_, stats, motion);
    Decision d = decisionOf(DecisionKind::DrawnOnStatistics);
    d.query_frame = stats.last_query_frame;
    d.count = static_cast<uint8_t>(r.visible_results);
    d.history = stats.results;
    d.interval = static_cast<float>(r.interval);
    d.next_query = static_cast<float>(r.since + r.interval);
    if (r.distance) d.flags |= kDecisionDistance;
    return d;
}

uint32_t StatisticalCuller::renderObjects(const BspTree& tree, const CullFrame& frame,
                                          uint32_t node, bool inside_frustum, RenderDevice& device,
                                          const Decision& why) {
    const FrustumPlanes& frustum = view_.frustum;
    if (!options_.object_queries) {
        drawNodeObjects(tree, node, view_, inside_frustum, device, why);
        return 0;
    }
    // A leaf with one object in view: the leaf's own decision (its statistics, its query on
    // bounds that are that object's box, or close to it) already was the object's.
    if (tree.node(node).isLeaf()) {
        uint32_t in_view = 0;
        forEachObjectInFrustum(tree, node, frustum, inside_frustum, [&](uint32_t) { ++in_view; });
        if (in_view <= 1) {
            drawNodeObjects(tree, node, view_, inside_frustum, device, why);
            return 0;
        }
    }
    uint32_t queries = 0;
    forEachObjectInFrustum(tree, node, view_, inside_frustum, [&](uint32_t o) {
        const Entry entry{0, o, Subject::Object, inside_frustum};
        const Aabb& box = tree.objectBox(o);
        const double draw_ms = costs_active_ ? costs_.drawMs(frame.object_triangles[o]) : 0.0;
        QueryContext context;
        Decision object_why;
        if (decide(frame, object_stats_[o], box, entry, draw_ms, 1, &context, &object_why) ==
            NodeAction::Render) {
            recordFor(entry, object_why);
            device.drawObject(o);
            return;
        }
        const QueryTag tag = QueryTag::object(o);
        if (drawsWhileRequerying(context)) {
            issueUpdate(tree, frame, entry, std::span<const Aabb>(&box, 1), tag, context, device);
            recordFor(entry, inFlightDecision(frame.frame_index));
            device.drawObject(o);
            return;
        }
        enqueue(device.issueQuery(box, tag), entry, context);
        ++queries;
    });
    return queries;
}

bool StatisticalCuller::process(const BspTree& tree, const CullFrame& frame, Entry entry,
                                RenderDevice& device) {
    if (entry.subject == Subject::Node) {
        NodeVisit visit{entry.index, entry.inside_frustum};
        bool inside = false;
        if (!nodeInFrustum(tree, visit, view_.frustum, &inside)) {  // SKIP
            recordFor(entry, decisionOf(DecisionKind::FrustumCulled));
            return false;
        }
        entry.inside_frustum = inside;
        const Aabb& box = tree.bounds(entry.index);
        const double draw_ms = costs_active_ ? subtree_draw_ms_[entry.index] : 0.0;
        QueryContext context;
        Decision why;
        if (decide(frame, stats_[entry.index], box, entry, draw_ms, 1, &context, &why) ==
            NodeAction::Render) {
            renderNode(tree, frame, entry, device, why);
            return false;
        }
        if (options_.descend_visible_inner_nodes && context.prior == PriorResult::LastVisible &&
            !tree.node(entry.index).isLeaf()) {
            // Improvement 8: its children decide; the interval runs again from now, as when the
            // cost model puts a query off, and the statistics keep their age.
            stats_[entry.index].deferred_time_s = frame.time_s;
            stats_[entry.index].deferred_travel_m = travelOf(entry);
            ++counters_.inner_descents;
            renderNode(tree, frame, entry, device, decisionOf(DecisionKind::DrawnNoTest));
            return false;
        }
        if (drawsWhileRequerying(context)) {
            issueUpdate(tree, frame, entry, std::span<const Aabb>(&box, 1),
                        QueryTag::node(entry.index), context, device);
            renderNode(tree, frame, entry, device, inFlightDecision(frame.frame_index));
            return false;
        }
        enqueue(device.issueQuery(box, QueryTag::node(entry.index)), entry, context);
        return true;
    }
    // A virtual leaf: the objects stored in the node itself that pass the frustum.
    if (options_.object_queries) {
        return renderObjects(tree, frame, entry.index, entry.inside_frustum, device,
                             decisionOf(DecisionKind::NoReasonGiven)) > 0;
    }
    boxes_.clear();
    Aabb box;
    double draw_ms = 0.0;
    forEachObjectInFrustum(tree, entry.index, view_, entry.inside_frustum, [&](uint32_t o) {
        boxes_.push_back(tree.objectBox(o));
        extend(box, tree.objectBox(o));
        if (costs_active_) draw_ms += costs_.drawMs(frame.object_triangles[o]);
    });
    if (boxes_.empty()) return false;
    const uint32_t query_boxes = static_cast<uint32_t>(boxes_.size());
    QueryContext context;
    Decision why;
    if (decide(frame, own_stats_[entry.index], box, entry, draw_ms, query_boxes, &context, &why) ==
        NodeAction::Render) {
        drawNodeObjects(tree, entry.index, view_, entry.inside_frustum, device, why);
        return false;
    }
    const QueryTag tag = QueryTag::nodeObjects(entry.index);
    if (drawsWhileRequerying(context)) {
        issueUpdate(tree, frame, entry, std::span<const Aabb>(boxes_), tag, context, device);
        drawNodeObjects(tree, entry.index, view_, entry.inside_frustum, device,
                        inFlightDecision(frame.frame_index));
        return false;
    }
    enqueue(device.issueQuery(std::span<const Aabb>(boxes_), std::span<const QueryTag>(&tag, 1)),
            entry, context);
    return true;
}

void StatisticalCuller::record(const Entry& e, const QueryContext& context, bool visible,
                               double time_s, double travel_m, uint64_t frame) {
    NodeStatistics& stats = statsOf(e);
    recordQueryResult(options_, stats, visible, time_s, travel_m);
    stats.last_query_frame = static_cast<uint32_t>(frame);
    estimates_[estimateIndex(context.prior, e.subject == Subject::Object)].add(!visible);
    ++counters_.answers;
    counters_.visible_answers += visible ? 1 : 0;
}

void StatisticalCuller::enqueue(QueryId id, const Entry& entry, const QueryContext& context) {
    double weight = 1.0;
    if (options_.weigh_in_flight) {
        const double visible =
            1.0 -
            estimates_[estimateIndex(context.prior, entry.subject == Subject::Object)].occluded;
        weight = std::max(visible, 1.0 / StatisticalOptions::kMaxRunAhead);
    }
    pending_.push_back({id, entry, context, weight});
    in_flight_weight_ += weight;
    waited_weight_ += weight;
    ++counters_.queries;
}

bool StatisticalCuller::answer(const BspTree& tree, const CullFrame& frame, const Pending& pending,
                               RenderDevice& device) {
    const Entry& e = pending.entry;
    const QueryAnswer a = device.takeAnswer(pending.id);
    record(e, pending.context, a.visible, frame.time_s, travelOf(e), frame.frame_index);
    const Decision why = answeredDecision(frame.frame_index, a);
    if (!a.visible) {
        recordFor(e, why);
        return a.waited;
    }
    switch (e.subject) {
        case Subject::Node:
            renderNode(tree, frame, e, device, why);
            break;
        case Subject::NodeObjects:
            drawNodeObjects(tree, e.index, view_, e.inside_frustum, device, why);
            break;
        case Subject::Object:
            recordFor(e, why);
            device.drawObject(e.index);
            break;
    }
    return a.waited;
}

void StatisticalCuller::issueUpdate(const BspTree& tree, const CullFrame& frame, const Entry& entry,
                                    std::span<const Aabb> boxes, const QueryTag& tag,
                                    const QueryContext& context, RenderDevice& device) {
    const uint32_t generation =
        entry.subject == Subject::Object ? 0 : tree.node(entry.index).generation;
    updates_.push_back({device.issueQuery(boxes, std::span<const QueryTag>(&tag, 1)), entry,
                        context, frame.time_s, travelOf(entry), generation, frame.frame_index});
    ++counters_.queries;
    ++counters_.update_queries;
}

void StatisticalCuller::collectUpdates(const BspTree& tree, RenderDevice& device,
                                       uint64_t older_than_frame) {
    while (updates_head_ < updates_.size()) {
        const Update& u = updates_[updates_head_];
        if (u.frame >= older_than_frame && !device.isQueryReady(u.id)) break;
        const bool visible = device.takeAnswer(u.id).visible;
        const bool same_subject = u.entry.subject == Subject::Object
                                      ? u.entry.index < object_stats_.size()
                                      : u.entry.index < tree.nodeCount() &&
                                            tree.node(u.entry.index).generation == u.generation;
        if (same_subject) record(u.entry, u.context, visible, u.time_s, u.travel_m, u.frame);
        ++updates_head_;
    }
    if (updates_head_ == updates_.size()) {
        updates_.clear();
        updates_head_ = 0;
    }
}

void StatisticalCuller::frustumOnlyFrame(const BspTree& tree, RenderDevice& device) {
    counters_.frustum_only = true;
    Decision why = decisionOf(DecisionKind::DrawnNoTest);
    why.flags = kDecisionFallback;
    traverseFrontToBack(tree, view_, vfc_stack_, [&](const NodeVisit& visit) {
        drawNodeObjects(tree, visit.node, view_, visit.inside_frustum, device, why);
        return true;
    });
}

// Fallback (improvement 5): after a frame that ran the algorithm, look at the share of visible
// answers over the window; when it is high enough, cull by the frustum only for a while.
void StatisticalCuller::endFrame(double now_s) {
    if (!options_.fallback) return;
    const uint32_t w = static_cast<uint32_t>(window_answers_.size());
    window_answers_[window_next_] = counters_.answers;
    window_visible_[window_next_] = counters_.visible_answers;
    window_next_ = (window_next_ + 1) % w;
    window_frames_ = std::min(window_frames_ + 1, w);
    if (window_frames_ < w) return;
    uint64_t answers = 0, visible = 0;
    for (uint32_t i = 0; i < w; ++i) {
        answers += window_answers_[i];
        visible += window_visible_[i];
    }
    if (answers >= uint64_t{kFallbackMinAnswersPerFrame} * w &&
        static_cast<double>(visible) >=
            options_.fallback_visible_share * static_cast<double>(answers)) {
        frustum_only_ = true;
        frustum_only_until_s_ = now_s + options_.fallback_recheck_s;
        window_frames_ = 0;  // the next look starts from a fresh window
    }
}

// With ready_answers: queries_before_restart, or with waits_per_frame the last frame's waited
// queries (weighed as the bound counts them) spread over that many waits, whichever is more.
double StatisticalCuller::inFlightBound() const {
    const double fixed = static_cast<double>(options_.queries_before_restart);
    if (options_.waits_per_frame == 0) return fixed;
    return std::max(fixed, last_waited_weight_ / static_cast<double>(options_.waits_per_frame));
}

void StatisticalCuller::cullAndRender(const BspTree& tree, const CullFrame& frame,
                                      RenderDevice& device) {
    counters_ = {};
    view_ = prepareView(frame);
    prepareFrame(tree, frame);
    if (frustum_only_) {
        if (frame.time_s < frustum_only_until_s_) {
            frustumOnlyFrame(tree, device);
            return;
        }
        frustum_only_ = false;  // re-check: run the algorithm again
    }

    heap_.clear();
    pending_.clear();
    pending_head_ = 0;
    in_flight_weight_ = 0.0;
    last_waited_weight_ = waited_weight_;
    waited_weight_ = 0.0;
    // Update answers from earlier frames first: the statistics they bring decide this frame. On
    // a GPU they are ready by now (the last frame was finished); those still in flight are
    // waited for, so that no answer lags more than a frame.
    collectUpdates(tree, device, frame.frame_index);
    if (!isEmpty(tree.bounds(tree.root()))) push({0, tree.root(), Subject::Node, false});

    // Takes the oldest pending answer; `work_left` says whether the main queue held anything.
    auto take_oldest = [&](bool work_left) {
        const Pending p = pending_[pending_head_++];
        in_flight_weight_ -= p.weight;
        if (answer(tree, frame, p, device)) {
            ++counters_.blocked_answers;
            counters_.blocked_with_work_left += work_left ? 1 : 0;
        }
        if (pending_head_ == pending_.size()) {
            pending_.clear();
            pending_head_ = 0;
            in_flight_weight_ = 0.0;  // no drift from the sums of weights
        }
    };

    if (!options_.ready_answers) {
        // The paper's loop: issue until the oldest answer is ready (or enough queries were
        // issued in this pass), then go back to the queue start and take every answer.
        while (!heap_.empty() || pending_head_ < pending_.size()) {
            uint32_t queries_this_pass = 0;
            while (!heap_.empty() && queries_this_pass < options_.queries_before_restart &&
                   !(pending_head_ < pending_.size() &&
                     device.isQueryReady(pending_[pending_head_].id))) {
                if (process(tree, frame, pop(), device)) ++queries_this_pass;
            }
            while (pending_head_ < pending_.size()) take_oldest(!heap_.empty());
        }
    } else {
        // Improvement 1: every answer is taken as soon as it is ready (answers become ready in
        // issue order, so only the oldest is polled), and the traversal goes on. The oldest
        // answer is waited for only when the main queue is empty, or when as many queries as
        // the paper lets one pass issue (queries_before_restart) are in flight: the paper's own
        // bound on how far the traversal may run ahead of its answers (farther nodes queried
        // before nearer ones are drawn come back visible more often).
        const double bound = inFlightBound();
        counters_.in_flight_bound = bound;
        while (true) {
            while (pending_head_ < pending_.size() &&
                   device.isQueryReady(pending_[pending_head_].id)) {
                take_oldest(!heap_.empty());
            }
            // Each weight is 1 without weigh_in_flight, so the sum is then the count.
            const size_t in_flight = pending_.size() - pending_head_;
            const bool room = in_flight_weight_ < bound - 1e-9;
            if (!heap_.empty() && room) {
                process(tree, frame, pop(), device);
            } else if (in_flight > 0) {
                take_oldest(false);
            } else {
                break;
            }
        }
    }
    collectUpdates(tree, device, 0);  // the ready ones; the rest are taken next frame
    endFrame(frame.time_s);
}

}  // namespace occsim
