// Occlusion culling with statistically optimised occlusion queries (Kovalčík & Sochor, WSCG 2005).
//
// Each node keeps the results of its recent queries. CalcNodeAction decides per node:
//   frustum-culled                              -> SKIP
//   near plane may cut its box (viewer inside)  -> RENDER (a clipped query could lie)
//   no statistics, or statistics too old        -> QUERY
//   last query said occluded                    -> QUERY
//   now > last_query_time + BASE_TIME * (a - b^occ_num)  -> QUERY
//   otherwise                                   -> RENDER without a query
// where occ_num is the number of unoccluded results in the node's history ("the decay curve";
// the paper uses a = 2, b = 0.5, BASE_TIME = 2/3 s). Time is simulation time.
//
// The traversal is the paper's two-queue scheme: nodes are taken front to back from the main
// queue; queries are issued without waiting and their nodes appended to the query queue; the
// main loop stops when the oldest query's answer is ready (or after `queries_before_restart`
// queries), then every pending result is taken in order and the children of visible nodes go
// back to the start of the main queue.
#pragma once

#include "culling/culler.h"
#include "culling/culler_options.h"
#include "culling/node_state.h"
#include "culling/traversal.h"

#include <deque>
#include <string>
#include <vector>

namespace occsim {

// What CalcNodeAction decides for a node that passed the frustum test (the paper's SKIP is the
// frustum test itself, made by the traversal before it asks).
enum class NodeAction : uint8_t { Render, Query };

struct NodeStatistics {
    double last_query_time_s = 0.0;
    uint32_t history = 0;  // bit i = result of the i-th most recent query (1 = visible)
    uint8_t results = 0;   // how many results the history holds (<= history_length)
};

// CalcNodeAction for a node that passed the frustum test; exposed for tests and the tuner.
NodeAction decideNodeAction(const StatisticalOptions& options, const NodeStatistics& stats,
                            bool near_plane_touches_box, double now_s);

// Records one query result into a node's history.
void recordQueryResult(const StatisticalOptions& options, NodeStatistics& stats, bool visible,
                       double now_s);

class StatisticalCuller final : public Culler {
public:
    explicit StatisticalCuller(const StatisticalOptions& options = {});
    std::string_view name() const override { return "statistical"; }
    void reset(const BspTree& tree) override;
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

    const StatisticalOptions& options() const { return options_; }
    const NodeStatistics& statistics(uint32_t node) const { return stats_[node]; }

private:
    struct PendingQuery {
        NodeVisit visit;
        QueryId id;
    };
    void renderVisibleNode(const BspTree& tree, const CullFrame& frame, const NodeVisit& visit,
                           RenderDevice& device);

    StatisticalOptions options_;
    NodeStateArray<NodeStatistics> stats_;
    std::vector<NodeVisit> queue_;  // the main queue; its start is the back of this stack
    std::deque<PendingQuery> query_queue_;
};

}  // namespace occsim
