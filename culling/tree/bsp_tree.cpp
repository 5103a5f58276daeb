// The axis-aligned BSP tree over moving objects declared in bsp_tree.h.
//
// Kovalčík & Sochor (2005, section "Overview") keep each object in the node that encompasses it
// "fully and as tightly as possible". With plain kD cells that is the deepest node whose cell
// contains the box, and every object that straddles a split plane stays in the inner node above
// it: in a dense field most objects end up high in the tree, where they are drawn whenever their
// large node is visible. Loose cells (Ulrich, "Loose Octrees", Game Programming Gems, 2000;
// Ericson, "Real-Time Collision Detection", section 7.3.6) let such an object go to the child on
// its centre's side, whose loose cell still contains it; since node bounds stay tight over the
// objects, what a culler queries is as tight as before, only nested less strictly.
//
// A moving object is re-placed by walking up from its current node only as far as needed and
// then down again; an object whose node still fits it needs no walk at all. Bounds are refitted
// lazily (only dirty nodes, children before parents), and the same pass splits leaves that movers
// crowded and merges subtrees they emptied, so the tree follows the scene without ever being
// rebuilt.
//
// Boxes that are not finite and ordered (NaN, infinite, inverted) cannot be placed by
// containment; they live in the root and make their subtree's bounds infinite, so that a culler
// never skips them on the evidence of a box that means nothing.
#include "occsim/culling/tree/bsp_tree.h"

#include <cassert>
#include <cmath>
#include <string>

#include "culling/tree/loose_cells.h"
#include "culling/tree/tree_builder.h"

namespace occsim {

using namespace bsp_detail;

bool BspBuildOptions::isValid(std::string* error) const {
    auto fail = [error](const std::string& message) {
        if (error != nullptr) *error = message;
        return false;
    };
    if (max_depth > 64) {
        return fail("max_depth must be in [0, 64], got " + std::to_string(max_depth));
    }
    if (max_objects_per_leaf < 1) {
        return fail("max_objects_per_leaf must be at least 1, got " +
                    std::to_string(max_objects_per_leaf));
    }
    if (!std::isfinite(root_margin) || root_margin < 0.0f || root_margin > 10.0f) {
        return fail("root_margin must be finite and in [0, 10], got " +
                    std::to_string(root_margin));
    }
    if (split_rule != BspSplitRule::Median && split_rule != BspSplitRule::Sah) {
        return fail("split_rule must be Median or Sah, got " +
                    std::to_string(static_cast<int>(split_rule)));
    }
    if (!std::isfinite(looseness) || looseness < 0.0f || looseness > 4.0f) {
        return fail("looseness must be finite and in [0, 4], got " + std::to_string(looseness));
    }
    if (!std::isfinite(max_root_growth) || max_root_growth < 1.0f || max_root_growth > 1e6f) {
        return fail("max_root_growth must be finite and in [1, 1e6], got " +
                    std::to_string(max_root_growth));
    }
    return true;
}

void BspTree::build(std::span<const Aabb> object_boxes, const BspBuildOptions& options) {
    assert(options.isValid(nullptr));
    assert(object_boxes.size() < kNone);
    const auto object_count = static_cast<uint32_t>(object_boxes.size());
    options_ = options;

    object_box_.assign(object_boxes.begin(), object_boxes.end());
    object_node_.assign(object_count, root());
    object_next_.assign(object_count, kNone);
    object_prev_.assign(object_count, kNone);

    nodes_.clear();
    free_slots_.clear();
    dirty_nodes_.clear();
    BspNode root_node;
    root_node.cell = rootCellFor(object_boxes, options.root_margin);
    root_node.loose_cell = rootLooseCell(root_node.cell, options_.looseness);
    built_root_cell_ = root_node.cell;
    nodes_.push_back(root_node);

    // Only boxes the root can hold take part in splitting; the rest stay in the root.
    std::vector<uint32_t> placeable;
    placeable.reserve(object_count);
    for (uint32_t object = 0; object < object_count; ++object) {
        const Aabb& box = object_box_[object];
        if (isPlaceable(box) && contains(nodes_[0].loose_cell, box)) placeable.push_back(object);
    }
    TreeBuilder builder(nodes_, object_box_, options_, object_node_, build_scratch_,
                        [this](uint32_t parent) { return allocateSlot(parent); });
    builder.buildSubtree(root(), placeable);

    // Linking in descending order leaves every node's list in ascending object order.
    for (uint32_t object = object_count; object-- > 0;) link(object, object_node_[object]);

    // The initial fit is part of build, not a refit: children (larger indices) first.
    for (uint32_t n = nodeCount(); n-- > 0;) computeBounds(n);

    // A new structure: every slot holds a new node.
    for (BspNode& node : nodes_) node.generation = next_generation_++;
    ++structure_version_;
}

// --- Storage: node slots and the object lists of nodes ----------------------------------------

uint32_t BspTree::allocateSlot(uint32_t parent) {
    // The lowest free slot above the parent keeps "a child's index exceeds its parent's" and the
    // array compact; without one, a new slot at the end.
    uint32_t slot;
    auto free = std::upper_bound(free_slots_.begin(), free_slots_.end(), parent);
    if (free != free_slots_.end()) {
        slot = *free;
        free_slots_.erase(free);
    } else {
        slot = nodeCount();
        nodes_.emplace_back();
    }
    BspNode& node = nodes_[slot];
    node = BspNode{};
    node.generation = next_generation_++;
    return slot;
}

void BspTree::freeSlot(uint32_t n) {
    BspNode& node = nodes_[n];
    const uint32_t generation = node.generation;
    node = BspNode{};
    node.live = false;
    node.generation = generation;  // a new one comes with the next node to use the slot
    free_slots_.insert(std::upper_bound(free_slots_.begin(), free_slots_.end(), n), n);
    // Free slots at the end of the array are dropped, so nodeCount() shrinks back.
    while (!free_slots_.empty() && free_slots_.back() == nodeCount() - 1) {
        free_slots_.pop_back();
        nodes_.pop_back();
    }
}

uint32_t BspTree::maxDepth() const {
    uint32_t deepest = 0;
    for (const BspNode& node : nodes_) {
        if (node.live) deepest = std::max(deepest, node.depth);
    }
    return deepest;
}

void BspTree::link(uint32_t object, uint32_t node) {
    BspNode& target = nodes_[node];
    object_prev_[object] = kNone;
    object_next_[object] = target.first_object;
    if (target.first_object != kNone) object_prev_[target.first_object] = object;
    target.first_object = object;
    ++target.object_count;
    object_node_[object] = node;
}

void BspTree::unlink(uint32_t object) {
    BspNode& source = nodes_[object_node_[object]];
    const uint32_t prev = object_prev_[object];
    const uint32_t next = object_next_[object];
    if (prev != kNone) {
        object_next_[prev] = next;
    } else {
        source.first_object = next;
    }
    if (next != kNone) object_prev_[next] = prev;
    object_prev_[object] = kNone;
    object_next_[object] = kNone;
    --source.object_count;
    object_node_[object] = kNone;
}

void BspTree::markDirtyToRoot(uint32_t node) {
    // A dirty node's ancestors are already dirty (marking always runs to the root), so the walk
    // can stop at the first dirty node.
    while (node != kNone && !nodes_[node].bounds_dirty) {
        nodes_[node].bounds_dirty = true;
        dirty_nodes_.push_back(node);
        node = nodes_[node].parent;
    }
}

}  // namespace occsim
