// Pieces the coherent hierarchical cullers (CHC and CHC++) share: the front-to-back traversal
// queue ordered by distance, the boxes a query on a node's own objects covers, and the
// classification of nodes into opened and termination nodes with its pull-up.
//
// Both papers allow a depth-first stack for kD-trees, but recommend the distance-ordered
// (breadth-first) priority queue: it processes the scene in depth layers, so nodes whose queries
// are in flight at the same time rarely occlude each other (Bittner & Wimmer, "Front-to-back
// scene traversal"), and CHC++ is written against it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/geometry/frustum.h"
#include "occsim/culling/tree/bsp_tree.h"
#include "occsim/culling/tree/node_state.h"
#include "occsim/culling/tree/traversal.h"

namespace occsim {

// What a coherent culler's query is for: what its answer decides, and so what the culler does
// with it. CHC uses every purpose but Multi (CHC++'s multiqueries).
enum class QueryPurpose : uint8_t {
    Invisible,  // one previously invisible node: the traversal waits for this answer
    Multi,      // several previously invisible nodes in one multiquery (CHC++)
    Visible,    // a previously visible leaf, already rendered: the answer is for the next frame
    Own,        // the own objects of an opened inner node, already rendered: likewise
};

// A min-heap of nodes keyed by the distance from the eye to their bounds. The storage is reused
// from frame to frame, so a steady state allocates nothing.
class DistanceQueue {
  public:
    void clear() { heap_.clear(); }
    bool empty() const { return heap_.empty(); }

    void push(const BspTree& tree, NodeVisit visit, glm::vec3 eye) {
        heap_.push_back({distanceSquared(tree.bounds(visit.node), eye), visit});
        std::push_heap(heap_.begin(), heap_.end(), Later{});
    }

    void pushChildren(const BspTree& tree, uint32_t node, glm::vec3 eye, bool inside_frustum) {
        const BspNode& n = tree.node(node);
        if (n.isLeaf()) return;
        push(tree, {n.child[0], inside_frustum}, eye);
        push(tree, {n.child[1], inside_frustum}, eye);
    }

    NodeVisit pop() {
        std::pop_heap(heap_.begin(), heap_.end(), Later{});
        const NodeVisit visit = heap_.back().visit;
        heap_.pop_back();
        return visit;
    }

  private:
    struct Entry {
        float distance_squared;
        NodeVisit visit;
    };
    // Orders the heap so that the nearest node comes out first; ties go to the lower node index,
    // so the order never depends on the heap's history.
    struct Later {
        bool operator()(const Entry& a, const Entry& b) const {
            if (a.distance_squared != b.distance_squared) {
                return a.distance_squared > b.distance_squared;
            }
            return a.visit.node > b.visit.node;
        }
    };
    std::vector<Entry> heap_;
};

// Appends the boxes of the objects stored in `node` itself that pass the frustum (the objects
// drawNodeObjects() would draw) and returns how many. In an inner node these are the straddlers:
// the node's own bounds cover its whole subtree, so a query on them would say nothing about the
// straddlers alone; the boxes of exactly the drawn objects do.
inline uint32_t appendOwnObjectBoxes(const BspTree& tree, uint32_t node,
                                     const FrustumPlanes& frustum, bool inside_frustum,
                                     std::vector<Aabb>& out) {
    uint32_t count = 0;
    forEachObjectInFrustum(tree, node, frustum, inside_frustum, [&](uint32_t o) {
        out.push_back(tree.objectBox(o));
        ++count;
    });
    return count;
}

// The classification CHC and CHC++ share (Bittner et al. 2004, "Coherent Hierarchical Culling",
// section 3; Mattausch et al. 2008 keep it): the previous frame's traversal ended at termination
// nodes, and each node visited this frame is reset to invisible until something found visible
// below it pulls it up again (the paper's shortcut that spares checking every child).
//
// Frames are stamped by calls to beginFrame() (0 = never visited), so "the previous frame" is
// the previous call even if a caller repeats a frame index; query scheduling uses the index.
class CoherentClassification {
  public:
    struct NodeState {
        uint64_t visited = 0;           // stamp of the last frame that visited the node
        uint64_t next_query = 0;        // first frame index its geometry is queried again
        uint64_t found_visible = 0;     // frame index of the last answer that found it visible
        uint32_t invisible_frames = 0;  // consecutive frames its queries found it invisible
        bool visible = false;
    };

    // What a visit found, for the culler to act on.
    enum class Visit : uint8_t {
        Culled,               // outside the frustum (or empty): skip the subtree
        NearPlane,            // the near plane may cut its box: never queried, traverse it
        PreviouslyInvisible,  // a termination node found invisible (or not reached) last frame
        PreviouslyVisible,    // opened last frame (or a visible leaf): traverse without waiting
    };

    void reset(const BspTree& tree) {
        state_.reset(tree);
        stamp_ = 0;
    }
    // Starts a frame on the tree as it is now (nodes new since the last frame start unclassified).
    void beginFrame(const BspTree& tree) {
        state_.sync(tree);
        ++stamp_;
    }

    // The common start of a node's visit: the frustum test (setting visit.inside_frustum), the
    // reset to invisible, and the near-plane rule (such a node is pulled up at once).
    Visit visit(const BspTree& tree, const PreparedView& view, NodeVisit& visit) {
        bool inside = false;
        if (!nodeInFrustum(tree, visit, view.frustum, &inside)) return Visit::Culled;
        visit.inside_frustum = inside;
        NodeState& s = state_[visit.node];
        const bool visited_last_frame = s.visited == stamp_ - 1;
        const bool was_visible = s.visible && visited_last_frame;
        // A node that was not a termination node last frame has no recent history to go on.
        if (!visited_last_frame) s.invisible_frames = 0;
        s.visible = false;
        s.visited = stamp_;
        if (nearPlaneTouchesBox(tree.bounds(visit.node), view.eye, view.near_radius)) {
            pullUp(tree, visit.node);
            return Visit::NearPlane;
        }
        return was_visible ? Visit::PreviouslyVisible : Visit::PreviouslyInvisible;
    }

    // Marks the node and its ancestors visible (pull-up).
    void pullUp(const BspTree& tree, uint32_t node) {
        while (node != BspTree::kNone && !state_[node].visible) {
            state_[node].visible = true;
            node = tree.node(node).parent;
        }
    }

    // A query found the node invisible once more (CHC++'s multiquery grouping uses the count).
    void markInvisible(uint32_t node, uint32_t cap) {
        NodeState& s = state_[node];
        s.invisible_frames = std::min(s.invisible_frames + 1, cap);
    }

    // Why a previously visible node's geometry is drawn: its query of this frame is queued or in
    // flight, or it is still assumed visible since the answer that found it visible.
    Decision previouslyVisible(uint32_t node, bool query_due, uint64_t frame) const {
        if (query_due) return inFlightDecision(frame);
        const NodeState& s = state_[node];
        Decision d = decisionOf(DecisionKind::DrawnAssumedVisible);
        d.query_frame = static_cast<uint32_t>(s.found_visible);
        d.next_query_frame = static_cast<uint32_t>(s.next_query);
        return d;
    }

    NodeState& operator[](uint32_t node) { return state_[node]; }
    const NodeState& operator[](uint32_t node) const { return state_[node]; }
    bool visitedThisFrame(uint32_t node) const { return state_[node].visited == stamp_; }

  private:
    NodeStateArray<NodeState> state_;
    uint64_t stamp_ = 0;
};

}  // namespace occsim
