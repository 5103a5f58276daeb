// An axis-aligned BSP tree (kD-tree splits) over a fixed set of objects that move.
//
// Contract
// - Nodes and objects are flat arrays indexed by uint32_t. Node 0 is the root; a child's index is
//   always greater than its parent's, so a reverse index scan visits children before parents.
// - The cell structure (split planes) is built once by build() and never changes afterwards.
//   Objects move between nodes with reinsert().
// - Each object lives in exactly one node: the deepest node whose cell contains its box fully
//   (closed containment, so a box touching a split plane from one side goes to that side; a box
//   straddling a split stays in the inner node). An object whose box leaves the root cell, or is
//   not finite, lives in the root.
// - bounds(node) is the tight box over every object in the node's subtree, valid after build()
//   and after refitDirtyBounds(); it may extend beyond the node's cell. An empty subtree has an
//   empty Aabb. A subtree holding a non-finite object box has infinite bounds (so a culler never
//   skips it on false evidence).
// - reinsert() walks up from the object's node only until a cell contains the new box, then down,
//   and marks the path's bounds dirty; refitDirtyBounds() recomputes only dirty nodes.
// - Node indices are stable while a node exists. nodeCount() is the number of slots; when the
//   structure changes, structureVersion() increases and every slot holding a new node gets a new
//   BspNode::generation, so per-node state kept elsewhere can be kept for unchanged nodes and
//   reset for new ones (culling/node_state.h).
// - Objects of a node form a doubly linked list threaded through per-object arrays (O(1) move);
//   iterate with firstObject(node) / nextObject(object) until kNone.
#pragma once

#include "culling/aabb.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

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

    // Returns false and says why when an option is out of range.
    bool isValid(std::string* error) const;
};

struct BspNode {
    Aabb cell;                     // the region of space this node covers (static)
    Aabb bounds;                   // tight bounds of its subtree's objects (dynamic)
    uint32_t parent = UINT32_MAX;  // kNone for the root
    uint32_t child[2] = {UINT32_MAX, UINT32_MAX};  // both kNone for a leaf; [0] is below the split
    uint32_t first_object = UINT32_MAX;            // head of this node's own object list
    uint32_t object_count = 0;                     // objects stored in this node itself
    uint32_t depth = 0;
    float split = 0.0f;  // split position along axis (inner nodes)
    uint8_t axis = 0;    // 0 = x, 1 = y, 2 = z (inner nodes)
    bool bounds_dirty = false;
    // Changes whenever this slot starts holding a new node (a build, or a local split reusing a
    // freed slot): per-node state that others keep (a culler's statistics) is stale when the
    // generation it was recorded for differs. See NodeStateArray (culling/node_state.h).
    uint32_t generation = 0;

    bool isLeaf() const { return child[0] == UINT32_MAX; }
};

struct BspStats {
    uint64_t reinserts = 0;        // reinsert() calls
    uint64_t reinserts_moved = 0;  // ... that moved the object to another node
    uint64_t nodes_walked = 0;     // nodes visited by reinsert walks (up and down)
    uint64_t nodes_refit = 0;      // nodes recomputed by refitDirtyBounds()
};

class BspTree {
public:
    static constexpr uint32_t kNone = UINT32_MAX;

    // Builds the cells over the given object boxes and places every object. Replaces any previous
    // tree. Options must be valid (asserted).
    void build(std::span<const Aabb> object_boxes, const BspBuildOptions& options);

    // Records the object's new box and moves it to the deepest node whose cell contains it.
    void reinsert(uint32_t object, const Aabb& new_box);

    // Recomputes the bounds of every node marked dirty since the last refit, children first.
    void refitDirtyBounds();

    uint32_t root() const { return 0; }
    uint32_t nodeCount() const { return static_cast<uint32_t>(nodes_.size()); }
    uint32_t objectCount() const { return static_cast<uint32_t>(object_box_.size()); }
    const BspNode& node(uint32_t n) const { return nodes_[n]; }
    const Aabb& bounds(uint32_t n) const { return nodes_[n].bounds; }
    uint32_t firstObject(uint32_t n) const { return nodes_[n].first_object; }
    uint32_t nextObject(uint32_t object) const { return object_next_[object]; }
    uint32_t nodeOf(uint32_t object) const { return object_node_[object]; }
    const Aabb& objectBox(uint32_t object) const { return object_box_[object]; }
    uint32_t maxDepth() const;
    // Increases with every change of the node structure (build, local split or merge), so that a
    // holder of per-node state knows when to look for nodes whose generation changed.
    uint64_t structureVersion() const { return structure_version_; }

    const BspStats& stats() const { return stats_; }
    void resetStats() { stats_ = {}; }

private:
    uint32_t findDeepestContaining(uint32_t start, const Aabb& box);
    void link(uint32_t object, uint32_t node);
    void unlink(uint32_t object);
    void markDirtyToRoot(uint32_t node);

    std::vector<BspNode> nodes_;
    std::vector<Aabb> object_box_;
    std::vector<uint32_t> object_node_;
    std::vector<uint32_t> object_next_;
    std::vector<uint32_t> object_prev_;
    std::vector<uint32_t> dirty_nodes_;  // each listed once (bounds_dirty guards duplicates)
    BspStats stats_;
    uint64_t structure_version_ = 0;
    uint32_t next_generation_ = 1;
};

}  // namespace occsim
