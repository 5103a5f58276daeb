// Kovalčík & Sochor, "Occlusion Culling with Statistically Optimized Occlusion Queries",
// WSCG 2005 short papers, section 3 (the two-queue traversal and the optimised CalcNodeAction).
#include "culling/statistical_culler.h"

#include <bit>
#include <cmath>

namespace occsim {

NodeAction decideNodeAction(const StatisticalOptions& options, const NodeStatistics& stats,
                            bool near_plane_touches_box, double now_s) {
    if (near_plane_touches_box) return NodeAction::Render;
    if (stats.results == 0) return NodeAction::Query;
    if (now_s - stats.last_query_time_s > options.max_statistics_age_s) return NodeAction::Query;
    if ((stats.history & 1u) == 0) return NodeAction::Query;  // last result: occluded
    const uint32_t mask = options.history_length >= 32 ? ~0u : ((1u << options.history_length) - 1u);
    const int occ_num = std::popcount(stats.history & mask);
    const double not_query_time =
        stats.last_query_time_s +
        options.base_time_s * (options.decay_a - std::pow(options.decay_b, occ_num));
    return now_s > not_query_time ? NodeAction::Query : NodeAction::Render;
}

void recordQueryResult(const StatisticalOptions& options, NodeStatistics& stats, bool visible,
                       double now_s) {
    stats.history = (stats.history << 1) | (visible ? 1u : 0u);
    if (stats.results < options.history_length) ++stats.results;
    stats.last_query_time_s = now_s;
}

StatisticalCuller::StatisticalCuller(const StatisticalOptions& options) : options_(options) {}

void StatisticalCuller::reset(const BspTree& tree) {
    stats_.reset(tree);
    queue_.clear();
    query_queue_.clear();
}

void StatisticalCuller::renderVisibleNode(const BspTree& tree, const CullFrame& frame,
                                          const NodeVisit& visit, RenderDevice& device) {
    drawNodeObjects(tree, visit.node, frame.view.frustum, visit.inside_frustum, device);
    pushChildrenFrontToBack(tree, visit.node, frame.view.eye, visit.inside_frustum, queue_);
}

void StatisticalCuller::cullAndRender(const BspTree& tree, const CullFrame& frame,
                                      RenderDevice& device) {
    stats_.sync(tree);
    queue_.clear();
    queue_.push_back({tree.root(), false});
    const double now = frame.time_s;

    while (!queue_.empty() || !query_queue_.empty()) {
        uint32_t queries_this_pass = 0;
        while (!queue_.empty() && queries_this_pass < options_.queries_before_restart &&
               !(!query_queue_.empty() && device.isQueryReady(query_queue_.front().id))) {
            NodeVisit visit = queue_.back();
            queue_.pop_back();
            bool inside = false;
            if (!nodeInFrustum(tree, visit, frame.view.frustum, &inside)) continue;  // SKIP
            visit.inside_frustum = inside;
            const bool near = nearPlaneTouchesBox(tree.bounds(visit.node), frame.view.eye,
                                                  frame.view.near_radius);
            switch (decideNodeAction(options_, stats_[visit.node], near, now)) {
                case NodeAction::Query:
                    query_queue_.push_back(
                        {visit, device.issueQuery(tree.bounds(visit.node), QueryTag::node(visit.node))});
                    ++queries_this_pass;
                    break;
                case NodeAction::Render:
                    renderVisibleNode(tree, frame, visit, device);
                    break;
            }
        }
        // Back to the queue start: take every pending answer, in issue order.
        while (!query_queue_.empty()) {
            const PendingQuery pending = query_queue_.front();
            query_queue_.pop_front();
            const bool visible = device.queryResult(pending.id) > 0;
            recordQueryResult(options_, stats_[pending.visit.node], visible, now);
            if (visible) renderVisibleNode(tree, frame, pending.visit, device);
        }
    }
}

}  // namespace occsim
