// CHC++ (Mattausch, Bittner & Wimmer, "CHC++: Coherent Hierarchical Culling Revisited",
// Eurographics 2008), as summarised in the PURE engine's occlusion-culling notes.
// It keeps CHC's classification (chc_culler.h: termination nodes, pull-up, pull-down) and changes
// how queries are scheduled:
//   - i-queue: previously invisible nodes are not queried at once but collected; when
//     `batch_size` of them wait (or there is nothing left to traverse) the render queue is
//     rendered and the whole batch is queried in one switch to query state.
//   - v-queue: previously visible nodes are rendered at once (through the render queue) and their
//     queries, whose results only matter for the next frame, wait in the v-queue; they are issued
//     to fill time when the traversal queue is empty and no result is ready, and at the end.
//   - render queue: nodes to render accumulate and are drawn just before a batch of queries, so
//     the engine switches between rendering and querying once per batch, not once per node.
//   - multiqueries: the nodes of a batch are sorted by how long they have been invisible and
//     grouped into queries over several boxes. A group whose query returns zero stays invisible
//     with one query; otherwise every node of it goes back to the i-queue for a query of its own.
//   - randomised sampling: a node that has just turned visible is first re-tested after a random
//     0 <= r < n_av frames (deterministic: a hash of the seed, node and frame), then every
//     n_av + 1 frames while it stays visible, so re-tests do not all fall on the same frame.
//   - tight bounds: with `tight_bounds_depth` d > 0 a node is queried with the boxes of its
//     descendants d levels down (and the boxes of the straddlers on the way) instead of its own.
//
// Grouping rule (CHC++ section 5.1): a node invisible for i frames is taken to stay invisible
// with probability p(i) = 0.99 - 0.7 e^-i; a group M costs 1 + (1 - prod p) |M| queries on
// average (the multiquery, plus one per node when it fails), and grows while |M| / cost grows.
//
// Objects in inner nodes, the near plane and double rendering are handled as in chc_culler.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "culling/cullers/coherent_traversal.h"
#include "occsim/culling/contract/culler.h"

namespace occsim {

// Mattausch, Bittner & Wimmer, "CHC++: Coherent Hierarchical Culling Revisited", Eurographics
// 2008, sections 4 (queues), 5.1 (multiqueries), 5.2 (randomised sampling) and 6 (tight bounds).
struct ChcppOptions {
    // n_av: frames a node found visible is assumed visible (no query) before the next test.
    // On the default teapot scenario (llvmpipe), n_av = 0 / 2 / 5 / 10 gives 280 / 176 / 146 /
    // 125 queries and 1004 / 1044 / 1126 / 1197 drawn objects per frame: 2 trades about even.
    uint32_t visible_frames_skip = 2;
    // Previously invisible nodes collected before a batch of queries is issued.
    uint32_t batch_size = 50;
    // Group previously invisible nodes into multiqueries (false: one query per node).
    bool multiqueries = true;
    // Query a node with its descendants' boxes this many levels down; 0 = its own box. On the
    // default teapot scenario 2 saves a few queries and drawn objects at every n_av.
    uint32_t tight_bounds_depth = 2;
    // Seeds the randomised first re-test of nodes that turned visible.
    uint64_t seed = 1;
};

// What the last frame did, beyond the device's counters.
struct ChcppFrameStats {
    uint32_t query_batches = 0;        // i-queue batches issued
    uint32_t state_changes = 0;        // switches between rendering and querying
    uint32_t multiqueries = 0;         // queries covering more than one node
    uint32_t multiquery_nodes = 0;     // nodes covered by those
    uint32_t failed_multiqueries = 0;  // multiqueries that found something visible
    uint32_t visible_queries = 0;      // v-queue queries (previously visible nodes)
    uint32_t fill_queries = 0;         // ... of them issued while waiting for a result
};

class ChcppCuller final : public Culler {
  public:
    explicit ChcppCuller(const ChcppOptions& options = {});
    void reset(const BspTree& tree) override;
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

    const ChcppOptions& options() const { return options_; }
    const ChcppFrameStats& frameStats() const { return stats_; }
    bool classifiedVisible(uint32_t node) const { return nodes_[node].visible; }
    // Whether the last frame's traversal reached the node (it passed the frustum test).
    bool visitedLastFrame(uint32_t node) const { return nodes_.visitedThisFrame(node); }
    // The first frame in which the geometry of a visible node is queried again.
    uint64_t nextQueryFrame(uint32_t node) const { return nodes_[node].next_query; }

  private:
    void clearQueues();  // empties every per-frame queue (they keep their capacity)
    // A query in flight: on one node, or (Multi) on a group of nodes kept in multi_nodes_.
    struct PendingQuery {
        QueryId id;
        uint32_t node;         // the queried node; BspTree::kNone for a multiquery
        uint32_t group_begin;  // Multi: the group is multi_nodes_[group_begin, + group_size)
        uint32_t group_size;   // Multi: nodes in the group; 0 otherwise
        bool inside_frustum;
        QueryPurpose purpose;
    };
    struct QueuedNode {
        uint32_t node;
        bool inside_frustum;
        bool single;           // i-queue: its multiquery failed, query it alone
        QueryPurpose purpose;  // v-queue: Visible or Own
    };
    enum class DeviceState : uint8_t { None, Render, Query };

    void visitNode(const BspTree& tree, const CullFrame& frame, NodeVisit visit);
    void handleResult(const BspTree& tree, const CullFrame& frame, const PendingQuery& query,
                      const QueryAnswer& answer, RenderDevice& device);
    // Queues the node's own objects for rendering (recording `why`) and its children.
    void traverseNode(const BspTree& tree, const CullFrame& frame, const NodeVisit& visit,
                      const Decision& why);
    uint64_t firstRetestFrame(uint32_t node) const;

    void issueBatch(const BspTree& tree, RenderDevice& device);
    void issueVisibleQuery(const BspTree& tree, RenderDevice& device);
    void flushRenderQueue(const BspTree& tree, RenderDevice& device);
    void appendQueryBoxes(const BspTree& tree, uint32_t node, uint32_t depth);
    void issueSingle(const BspTree& tree, RenderDevice& device, const QueuedNode& node);
    void enterState(DeviceState state);

    ChcppOptions options_;
    PreparedView view_;  // this frame's view with its plane table (prepareView)
    ChcppFrameStats stats_;
    CoherentClassification nodes_;
    DistanceQueue traversal_queue_;
    std::vector<PendingQuery> query_queue_;  // FIFO: [query_head_, size) are in flight
    size_t query_head_ = 0;
    std::vector<QueuedNode> i_queue_;
    std::vector<QueuedNode> v_queue_;  // FIFO: [v_head_, size) wait for their query
    size_t v_head_ = 0;
    std::vector<NodeVisit> render_queue_;
    std::vector<QueuedNode> multi_nodes_;  // the nodes of this frame's multiqueries
    std::vector<uint32_t> order_;          // scratch: i-queue entries in grouping order
    std::vector<Aabb> boxes_;              // scratch: the boxes of the query being issued
    std::vector<QueryTag> tags_;           // scratch: the nodes a multiquery decides
    DeviceState device_state_ = DeviceState::None;
    uint64_t frame_ = 0;  // the frame index being rendered
};

}  // namespace occsim
