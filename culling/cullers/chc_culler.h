// Coherent Hierarchical Culling (Bittner, Wimmer, Piringer & Purgathofer, "Coherent Hierarchical
// Culling: Hardware Occlusion Queries Made Useful", Eurographics 2004), as written up by Bittner
// & Wimmer in their book chapter on online occlusion culling.
//
// The traversal of the previous frame ended at termination nodes: leaves found visible, and the
// largest nodes found invisible (each with a visible parent). This frame, front to back:
//   - an opened node (inner, visible last frame) is traversed without a query;
//   - a previously visible leaf is queried and rendered at once; its result only updates the
//     classification for the next frame;
//   - a previously invisible node (or one not visited last frame) is queried, and the traversal
//     goes on with other nodes while the result is in the query queue; a visible result
//     traverses it (pull-down), an invisible one culls its subtree.
// Every visited node is first reset to invisible; a visible result (or a node rendered on
// assumption) marks it and its ancestors visible (pull-up), so an inner node ends the frame
// visible exactly when something below it was. The query queue is checked before every node
// taken from the traversal queue, and waited on only when there is nothing left to traverse.
//
// The two optional optimisations of "Further Optimizations":
//   - conservative visibility testing: a leaf found visible is assumed visible, without a query,
//     for `visible_frames_skip` frames (t_av);
//   - approximate visibility (n_vp): the pixel threshold every query-based culler shares
//     (ApproximationOptions, applied by ApproximateDevice). With n_vp > 0 the result is no
//     longer conservative.
//
// Beyond the paper (which keeps geometry in leaves only):
//   - Objects in inner nodes (straddlers) are drawn whenever their node is traversed. A visible
//     inner node with such objects treats them as a virtual leaf: while the node stays opened,
//     the boxes of those objects are queried (in flight, like a visible leaf's query), so the
//     node stays open for them even when all its children turn invisible.
//   - A node whose box the near plane may cut is never queried (a clipped query could report
//     zero samples for a visible box): it is traversed as visible.
//   - A previously visible leaf whose result comes back visible is not traversed again (it was
//     rendered when it was visited), so no object is drawn twice in a frame.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "culling/cullers/coherent_traversal.h"
#include "occsim/culling/contract/culler.h"

namespace occsim {

// Bittner, Wimmer, Piringer & Purgathofer, "Coherent Hierarchical Culling: Hardware Occlusion
// Queries Made Useful", Eurographics 2004, "Further Optimizations". The paper's approximate
// visibility (n_vp) is the pixel threshold of ApproximationOptions, shared by every culler.
struct ChcOptions {
    // t_av: frames a leaf found visible is assumed visible without a query. 0 = every previously
    // visible leaf is queried every frame (the basic algorithm).
    uint32_t visible_frames_skip = 0;
};

class ChcCuller final : public Culler {
  public:
    explicit ChcCuller(const ChcOptions& options = {});
    void reset(const BspTree& tree) override;
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

    const ChcOptions& options() const { return options_; }
    // The classification the last frame left behind: the next frame's opened nodes are the
    // visited inner nodes that are visible, its termination nodes the other visited nodes.
    bool classifiedVisible(uint32_t node) const { return nodes_[node].visible; }
    // Whether the last frame's traversal reached the node (it passed the frustum test).
    bool visitedLastFrame(uint32_t node) const { return nodes_.visitedThisFrame(node); }

  private:
    struct PendingQuery {
        QueryId id;
        uint32_t node;
        bool inside_frustum;
        QueryPurpose purpose;  // Invisible, Visible or Own
    };
    void visitNode(const BspTree& tree, const CullFrame& frame, NodeVisit visit,
                   RenderDevice& device);
    void handleResult(const BspTree& tree, const CullFrame& frame, const PendingQuery& query,
                      const QueryAnswer& answer, RenderDevice& device);
    // Draws the node's own objects (recording `why`) and queues its children.
    void traverseNode(const BspTree& tree, const CullFrame& frame, const NodeVisit& visit,
                      RenderDevice& device, const Decision& why);

    void issue(RenderDevice& device, std::span<const Aabb> boxes, const NodeVisit& visit,
               QueryPurpose purpose);

    ChcOptions options_;
    PreparedView view_;  // this frame's view with its plane table (prepareView)
    CoherentClassification nodes_;
    DistanceQueue traversal_queue_;
    std::vector<PendingQuery> query_queue_;  // FIFO: [query_head_, size) are in flight
    size_t query_head_ = 0;
    std::vector<Aabb> boxes_;  // scratch for own-object queries
    uint64_t frame_ = 0;       // the frame index being rendered
};

}  // namespace occsim
