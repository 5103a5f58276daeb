// An axis-aligned BSP tree (kD-tree splits) with loose cells over a fixed set of objects that
// move. docs/bsp-tree.md describes the design and its measured effect.
//
// Contract
// - Nodes and objects are flat arrays indexed by uint32_t. Node 0 is the root; a child's index is
//   always greater than its parent's, so a reverse index scan visits children before parents and
//   a forward scan parents before children. Slots freed by a merge are reused only under that
//   rule; until then they are unused (isLive() false: no parent, no children, no objects, empty
//   bounds), and whoever scans 0..nodeCount() skips them.
// - Each node has a cell (the region its split planes bound) and a loose cell: the cell grown on
//   every side (loose octrees, Ulrich, "Loose Octrees", Game Programming Gems, 2000). The root's
//   margin along each axis is BspBuildOptions::looseness times its extent; both children of a
//   node get the same margin along its split axis (looseness times the larger child's extent
//   there, at most the parent's margin) and inherit the parent's along the others. So loose
//   cells nest, and siblings' loose cells differ only along their split axis.
// - Each object lives in exactly one node: following its box centre down from the root (a centre
//   on a split plane goes below), the deepest node whose loose cell contains the box. So its
//   node's cell contains its centre and its loose cell its box, and no child's loose cell contains
//   the box (the other child's cannot when the centre's child's does not: same margin, up to the
//   rounding of split +- margin). A box
//   straddling a split plane still reaches the child of its centre, so objects reach nodes of
//   about their own size. A box that is not finite, or that the root's loose cell does not
//   contain, lives in the root; a centre outside the root cell follows its nearest point in it.
// - bounds(node) is the tight box over every object in the node's subtree, valid after build()
//   and after refitDirtyBounds(); it may extend beyond the node's cell and loose cell. An empty
//   subtree has an empty Aabb. A subtree holding a non-finite object box has infinite bounds (so
//   a culler never skips it on false evidence).
// - reinsert() leaves an object whose node still holds it (cell contains the centre, loose cell
//   the box, no child takes it) where it is, without a walk; otherwise it walks up only until a
//   node holds the new box, then down the centre's path. It marks the changed nodes' bounds dirty.
// - The tree adapts locally and is never rebuilt (unless BspBuildOptions::adapt is false):
//   * a finite box leaving the root cell grows the root cell and the cells on that boundary, at
//     once in reinsert(), up to max_root_growth times the built root's largest extent;
//   * refitDirtyBounds() merges an inner node whose children are both leaves once its subtree
//     holds at most max_objects_per_leaf / 2 objects (or one child is empty and the subtree holds
//     at most max_objects_per_leaf: the parent's bounds would repeat the other child's), and splits
//     a leaf that movers crowded beyond max_objects_per_leaf by rebuilding the small subtree around
//     it (from its highest ancestor holding at most 2 x max_objects_per_leaf objects) as the build
//     would have. The gap between the two limits keeps a mover passing by from splitting and
//     merging the same node over and over.
// - Per-node state kept elsewhere: node indices are stable while a node exists. When the
//   topology changes (build, split, merge) structureVersion() increases and every slot that starts
//   holding a new node gets a new BspNode::generation; a node that only changes its cell (root
//   growth), becomes a leaf (merge) or an inner node (split) keeps its generation. So per-node
//   state (occsim/culling/tree/node_state.h) is kept for unchanged nodes and reset for new ones.
// - Objects of a node form a doubly linked list threaded through per-object arrays (O(1) move);
//   iterate with firstObject(node) / nextObject(object) until kNone.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "occsim/culling/geometry/aabb.h"

namespace occsim {

enum class BspSplitRule : uint8_t {
    Median,  // split the longest axis of the cell at the median of object centres
    Sah,     // surface area heuristic over a few candidate planes per axis
};

struct BspBuildOptions {
    uint32_t max_depth = 20;            // the root has depth 0
    uint32_t max_objects_per_leaf = 4;  // stop splitting a cell holding at most this many objects
    BspSplitRule split_rule = BspSplitRule::Median;
    // Extra margin around the scene's bounds for the root cell, as a fraction of its extent, so
    // movers that stray a little still find a cell below the root.
    float root_margin = 0.05f;
    // How far loose cells reach past their cells: the root's by this fraction of its extent on
    // each side (per axis), a child's by this fraction of the larger sibling's extent along its
    // parent's split axis (see the contract above). 0 gives the classic tree (straddlers stay in
    // inner nodes); 0.5 is the loose octree's loose cell of twice the cell's size, which holds
    // any object no larger than the cell that its centre lies in.
    float looseness = 0.5f;
    // Local adaptation to movers (root growth, leaf splits, merges). Off: the cells built once
    // never change, as in Kovalčík & Sochor.
    bool adapt = true;
    // The root cell grows to take movers that leave it, to at most this many times the built root
    // cell's largest extent on any axis; a box beyond that lives in the root.
    float max_root_growth = 16.0f;

    // Returns false and says why when an option is out of range.
    bool isValid(std::string* error) const;
};

struct BspNode {
    Aabb cell;        // the region its split planes bound (changes only by root growth)
    Aabb loose_cell;  // cell grown by the looseness: what placement tests
    Aabb bounds;      // tight bounds of its subtree's objects (dynamic)
    uint32_t parent = UINT32_MAX;                  // kNone for the root
    uint32_t child[2] = {UINT32_MAX, UINT32_MAX};  // both kNone for a leaf; [0] is below the split
    uint32_t first_object = UINT32_MAX;            // head of this node's own object list
    uint32_t object_count = 0;                     // objects stored in this node itself
    uint32_t subtree_object_count = 0;             // ... and in its descendants (valid with bounds)
    uint32_t depth = 0;
    float split = 0.0f;  // split position along axis (inner nodes)
    uint8_t axis = 0;    // 0 = x, 1 = y, 2 = z (inner nodes)
    bool bounds_dirty = false;
    bool live = true;  // false: a slot freed by a merge, holding no node until reused
    // Changes whenever this slot starts holding a new node (a build, or a node a local split
    // creates, in a new or a freed slot): per-node state that others keep (a culler's statistics)
    // is stale when the generation it was recorded for differs. See NodeStateArray
    // (occsim/culling/tree/node_state.h).
    uint32_t generation = 0;

    bool isLeaf() const { return child[0] == UINT32_MAX; }
};

struct BspStats {
    uint64_t reinserts = 0;           // reinsert() calls
    uint64_t reinserts_moved = 0;     // ... that moved the object to another node
    uint64_t reinserts_in_place = 0;  // ... whose node still fitted the new box: no walk
    uint64_t nodes_walked = 0;        // nodes visited by placement walks (up and down), counting
                                      // the node a walk starts from
    uint64_t nodes_refit = 0;         // nodes recomputed by refitDirtyBounds()
    uint64_t splits = 0;              // crowded leaves split (the small subtree around rebuilt)
    uint64_t nodes_created = 0;       // nodes those splits created (replacing the ones freed)
    uint64_t merges = 0;              // inner nodes turned into leaves (two nodes freed each)
    uint64_t root_growths = 0;        // times the root cell grew to take a box that left it
};

// Scratch of the subtree builder behind build(), leaf splits and split checks. The tree keeps it,
// so that the splits and split checks movers cause allocate nothing once it has grown.
struct BspBuildScratch {
    std::vector<float> centres;
    std::vector<float> candidates;
    std::vector<float> sorted;
};

class BspTree {
  public:
    static constexpr uint32_t kNone = UINT32_MAX;

    // Builds the cells over the given object boxes and places every object. Replaces any previous
    // tree. Options must be valid (asserted).
    void build(std::span<const Aabb> object_boxes, const BspBuildOptions& options);

    // Records the object's new box and moves it to where the placement rule puts it (see the
    // contract above); grows the root cell first when the box left it.
    void reinsert(uint32_t object, const Aabb& new_box);

    // Applies the local splits and merges the reinsertions since the last call asked for, and
    // recomputes the bounds of every node marked dirty, children first. Call once per frame after
    // the frame's reinsertions.
    void refitDirtyBounds();

    uint32_t root() const { return 0; }
    uint32_t nodeCount() const { return static_cast<uint32_t>(nodes_.size()); }
    uint32_t liveNodeCount() const {
        return nodeCount() - static_cast<uint32_t>(free_slots_.size());
    }
    bool isLive(uint32_t n) const { return nodes_[n].live; }
    uint32_t objectCount() const { return static_cast<uint32_t>(object_box_.size()); }
    const BspNode& node(uint32_t n) const { return nodes_[n]; }
    const Aabb& bounds(uint32_t n) const { return nodes_[n].bounds; }
    uint32_t firstObject(uint32_t n) const { return nodes_[n].first_object; }
    uint32_t nextObject(uint32_t object) const { return object_next_[object]; }
    uint32_t nodeOf(uint32_t object) const { return object_node_[object]; }
    const Aabb& objectBox(uint32_t object) const { return object_box_[object]; }
    const BspBuildOptions& options() const { return options_; }
    const Aabb& builtRootCell() const { return built_root_cell_; }
    uint32_t maxDepth() const;
    // Increases with every change of the node topology (build, local split or merge), so that a
    // holder of per-node state knows when to look for nodes whose generation changed.
    uint64_t structureVersion() const { return structure_version_; }

    // The child of node `n` that takes `box` by the placement rule (the child on the centre's side,
    // if its loose cell contains the box), or kNone (a leaf, or that child does not fit it).
    uint32_t childTaking(uint32_t n, const Aabb& box) const;

    const BspStats& stats() const { return stats_; }
    void resetStats() { stats_ = {}; }

  private:
    // Moves the object (its box already stored) to where the placement rule puts it.
    void relocate(uint32_t object, bool is_reinsert);
    void growRootToward(const Aabb& box);
    void growFace(uint32_t n, int axis, int side, float position);
    void splitCrowdedLeaf(uint32_t leaf);
    bool canSplit(uint32_t leaf);
    void freeDescendants(uint32_t n);
    void mergeChildren(uint32_t n);
    uint32_t allocateSlot(uint32_t parent);
    void freeSlot(uint32_t n);
    void computeBounds(uint32_t n);
    void link(uint32_t object, uint32_t node);
    void unlink(uint32_t object);
    void markDirtyToRoot(uint32_t node);

    BspBuildOptions options_;
    Aabb built_root_cell_;
    std::vector<BspNode> nodes_;
    std::vector<uint32_t> free_slots_;  // unused slots, ascending
    std::vector<Aabb> object_box_;
    std::vector<uint32_t> object_node_;
    std::vector<uint32_t> object_next_;
    std::vector<uint32_t> object_prev_;
    std::vector<uint32_t> dirty_nodes_;  // each listed once (bounds_dirty guards duplicates)
    struct SplitCandidate {
        uint32_t node;
        uint32_t generation;
    };
    std::vector<SplitCandidate> split_candidates_;  // crowded dirty leaves, for refitDirtyBounds()
    std::vector<uint32_t> scratch_objects_;
    std::vector<uint32_t> scratch_nodes_;
    std::vector<uint32_t> scratch_stack_;
    BspBuildScratch build_scratch_;
    BspStats stats_;
    uint64_t structure_version_ = 0;
    uint32_t next_generation_ = 1;
};

}  // namespace occsim
