// How the BSP tree follows its moving objects (bsp_tree.h): reinsertion by walking up only as far
// as needed and down again, growing the root toward objects that leave it, lazy refits of dirty
// bounds, and the splits and merges that keep leaves neither crowded nor empty (bsp_tree.cpp
// explains the tree itself).
#include <algorithm>
#include <cassert>
#include <cmath>

#include "culling/tree/loose_cells.h"
#include "culling/tree/tree_builder.h"
#include "occsim/culling/tree/bsp_tree.h"

namespace occsim {
namespace {

// When the root cell grows, it grows past the box by this fraction of its extent, so that a mover
// drifting outwards makes the root grow geometrically often, not every frame.
constexpr float kRootGrowthSlack = 0.25f;

}  // namespace

using namespace bsp_detail;

void BspTree::reinsert(uint32_t object, const Aabb& new_box) {
    assert(object < objectCount());
    ++stats_.reinserts;
    object_box_[object] = new_box;
    if (options_.adapt && isPlaceable(new_box) && !contains(nodes_[root()].cell, new_box)) {
        growRootToward(new_box);
    }
    relocate(object, true);
}

uint32_t BspTree::childTaking(uint32_t n, const Aabb& box) const {
    const BspNode& node = nodes_[n];
    if (node.isLeaf()) return kNone;
    const int side = takingSide(nodes_[node.child[0]].loose_cell, nodes_[node.child[1]].loose_cell,
                                node.axis, node.split, box);
    return side < 0 ? kNone : node.child[side];
}

void BspTree::relocate(uint32_t object, bool is_reinsert) {
    const Aabb& box = object_box_[object];
    const uint32_t start = object_node_[object];
    uint32_t target = root();
    ++stats_.nodes_walked;  // the node the walk starts from
    if (isPlaceable(box)) {
        // A node holds the box when it lies on the centre's path and its loose cell contains
        // the box. On the path: the centre is on the node's side of every ancestor's split, i.e.
        // in its cell with a centre on a split plane counted below (so the cell's lower face is
        // open, except where it is the root's). A centre outside the root cell follows its
        // nearest point in it (the split planes lie inside the root cell, so they order both
        // points alike).
        const Aabb& root_cell = nodes_[root()].cell;
        const glm::vec3 centre = glm::clamp(centreOf(box), root_cell.min, root_cell.max);
        auto holds = [&](uint32_t n) {
            const BspNode& candidate = nodes_[n];
            for (int axis = 0; axis < 3; ++axis) {
                if (centre[axis] > candidate.cell.max[axis]) return false;
                if (centre[axis] <= candidate.cell.min[axis] &&
                    candidate.cell.min[axis] != root_cell.min[axis]) {
                    return false;
                }
            }
            return contains(candidate.loose_cell, box);
        };
        uint32_t node = start;
        if (holds(node) && childTaking(node, box) == kNone) {
            // Still fits its node and no child: the common case for a small move, no walk.
            if (is_reinsert) ++stats_.reinserts_in_place;
        } else {
            // Up until a node holds the box (loose cells nest, so every ancestor of it would too:
            // the descent from there is the one from the root), then down the centre's path
            // while a child takes it.
            while (node != root() && !holds(node)) {
                node = nodes_[node].parent;
                ++stats_.nodes_walked;
            }
            if (contains(nodes_[node].loose_cell, box)) {
                for (uint32_t next = childTaking(node, box); next != kNone;
                     next = childTaking(node, box)) {
                    node = next;
                    ++stats_.nodes_walked;
                }
            }
        }
        target = node;
    }
    if (target != start) {
        unlink(object);
        link(object, target);
        if (is_reinsert) ++stats_.reinserts_moved;
    }
    // The box changed even if the node did not, so the node's bounds (and its ancestors') must be
    // refitted; the old node's subtree lost the object's old box.
    markDirtyToRoot(start);
    markDirtyToRoot(target);
}

void BspTree::growRootToward(const Aabb& box) {
    // The new root cell: past the box by a slack on every side where the box left the cell, and
    // never more than max_root_growth times the built root's largest extent on any axis. A box
    // beyond that (a mover lost far away) makes no growth and lives in the root.
    const Aabb old_cell = nodes_[root()].cell;
    const glm::vec3 built_size = extent(built_root_cell_);
    const float cap =
        options_.max_root_growth * std::max(built_size.x, std::max(built_size.y, built_size.z));
    Aabb cell = old_cell;
    for (int axis = 0; axis < 3; ++axis) {
        const float low = std::min(old_cell.min[axis], box.min[axis]);
        const float high = std::max(old_cell.max[axis], box.max[axis]);
        if (!(high - low <= cap)) return;  // beyond the cap (or overflowing): no growth at all
        const float slack = kRootGrowthSlack * (old_cell.max[axis] - old_cell.min[axis]);
        float slack_low = box.min[axis] < old_cell.min[axis] ? slack : 0.0f;
        float slack_high = box.max[axis] > old_cell.max[axis] ? slack : 0.0f;
        const float spare = cap - (high - low);
        if (slack_low + slack_high > spare) {  // the slack shrinks to stay within the cap
            const float scale = spare / (slack_low + slack_high);
            slack_low *= scale;
            slack_high *= scale;
        }
        cell.min[axis] = std::min(low - slack_low, low);
        cell.max[axis] = std::max(high + slack_high, high);
    }

    scratch_nodes_.clear();
    for (int axis = 0; axis < 3; ++axis) {
        if (cell.min[axis] < old_cell.min[axis]) growFace(root(), axis, 0, cell.min[axis]);
        if (cell.max[axis] > old_cell.max[axis]) growFace(root(), axis, 1, cell.max[axis]);
    }
    ++stats_.root_growths;

    // The grown cells' children grew too, so an object left in a grown inner node (no child fitted
    // it before) may fit a child now. Only those can: every other node's cell and children are
    // unchanged. Each grown node is listed once per face it grew on; relocating twice is harmless.
    scratch_objects_.clear();
    for (uint32_t n : scratch_nodes_) {
        if (nodes_[n].isLeaf()) continue;
        for (uint32_t o = nodes_[n].first_object; o != kNone; o = object_next_[o]) {
            scratch_objects_.push_back(o);
        }
    }
    std::sort(scratch_objects_.begin(), scratch_objects_.end());
    scratch_objects_.erase(std::unique(scratch_objects_.begin(), scratch_objects_.end()),
                           scratch_objects_.end());
    for (uint32_t o : scratch_objects_) relocate(o, false);
}

void BspTree::growFace(uint32_t n, int axis, int side, float position) {
    // The boundary cells on that face move with the root's face: a child touches the face unless
    // its parent splits this axis and it lies on the other side.
    uint32_t stack_top = 0;
    scratch_stack_.clear();
    scratch_stack_.push_back(n);
    while (stack_top < scratch_stack_.size()) {
        const uint32_t m = scratch_stack_[stack_top++];
        BspNode& node = nodes_[m];
        // The face moves, and the loose cell's face with it: margins stay as built, so loose
        // cells still nest and siblings still share their margin along their split axis.
        float& face = (side == 0 ? node.cell.min : node.cell.max)[axis];
        float& loose_face = (side == 0 ? node.loose_cell.min : node.loose_cell.max)[axis];
        loose_face += position - face;
        face = position;
        scratch_nodes_.push_back(m);
        if (node.isLeaf()) continue;
        if (node.axis == axis) {
            scratch_stack_.push_back(node.child[side]);
        } else {
            scratch_stack_.push_back(node.child[0]);
            scratch_stack_.push_back(node.child[1]);
        }
    }
}

void BspTree::refitDirtyBounds() {
    // Children have larger indices than parents: descending order refits children first, so a
    // parent reads its children's fresh bounds and object counts. std::sort works in place.
    std::sort(dirty_nodes_.begin(), dirty_nodes_.end(), std::greater<uint32_t>());
    split_candidates_.clear();
    for (uint32_t n : dirty_nodes_) {
        computeBounds(n);
        const BspNode& node = nodes_[n];
        if (options_.adapt && node.isLeaf() && node.object_count > options_.max_objects_per_leaf) {
            split_candidates_.push_back({n, node.generation});
        }
    }
    stats_.nodes_refit += dirty_nodes_.size();

    if (options_.adapt) {
        // Local adaptation, only where something changed, after every bound is fresh: neither
        // changes the bounds or object count of any node that stays.
        // Merges first, children before parents, so that an emptied subtree collapses in one
        // pass. A merge frees two slots above its node (already passed in this order) and reuses
        // none, so the nodes still to come are untouched.
        // A pair of leaves merges when it holds at most half a leaf's worth, or when one of
        // them is empty and the other would make an allowed leaf: the parent's bounds are then
        // the other leaf's, and a culler would query the same box twice.
        const uint32_t max_leaf = options_.max_objects_per_leaf;
        for (uint32_t n : dirty_nodes_) {
            const BspNode& node = nodes_[n];
            if (node.isLeaf()) continue;
            const BspNode& below = nodes_[node.child[0]];
            const BspNode& above = nodes_[node.child[1]];
            if (!below.isLeaf() || !above.isLeaf()) continue;
            const uint32_t count = node.subtree_object_count;
            const bool one_empty = below.object_count == 0 || above.object_count == 0;
            if (count <= max_leaf / 2 || (one_empty && count <= max_leaf)) mergeChildren(n);
        }
        // Then crowded leaves. A rebuild may free and reuse the slot of a later candidate: the
        // generation tells (a node built just now holds no more than the build allows).
        for (const SplitCandidate& candidate : split_candidates_) {
            if (candidate.node >= nodeCount()) continue;
            const BspNode& node = nodes_[candidate.node];
            if (!node.live || node.generation != candidate.generation || !node.isLeaf()) continue;
            splitCrowdedLeaf(candidate.node);
        }
    }
    dirty_nodes_.clear();  // keeps its capacity
}

void BspTree::computeBounds(uint32_t n) {
    BspNode& node = nodes_[n];
    Aabb bounds;
    bool infinite = false;
    for (uint32_t object = node.first_object; object != kNone; object = object_next_[object]) {
        const Aabb& box = object_box_[object];
        if (!isPlaceable(box)) {
            infinite = true;
            break;  // nothing can widen infinite bounds
        }
        extend(bounds, box);
    }
    uint32_t subtree = node.object_count;
    for (uint32_t child : node.child) {
        if (child == kNone) continue;
        extend(bounds, nodes_[child].bounds);
        subtree += nodes_[child].subtree_object_count;
    }
    node.bounds = infinite ? infiniteAabb() : bounds;
    node.subtree_object_count = subtree;
    node.bounds_dirty = false;
}

void BspTree::splitCrowdedLeaf(uint32_t leaf) {
    if (!canSplit(leaf)) return;  // identical boxes, or at max_depth: splitting changes nothing

    // Splitting just the leaf would add a level on every pass of a mover and leave chains of
    // nodes with the same bounds (the merge limit is lower, so they stay): instead the small
    // subtree around the leaf is rebuilt as the build would have built it. Its top is the highest
    // ancestor whose subtree holds at most twice max_objects_per_leaf objects, so a rebuild is
    // never big. That top keeps its generation (it covers the same objects); the nodes below it
    // are new.
    const uint32_t limit = 2 * options_.max_objects_per_leaf;
    uint32_t top = leaf;
    while (top != root() && nodes_[nodes_[top].parent].subtree_object_count <= limit) {
        top = nodes_[top].parent;
    }

    // Every object below the top (the top's own too) goes back into the build. Objects a cell
    // cannot hold (in the root: boxes that are not finite or lie beyond its loose cell) stay.
    scratch_objects_.clear();
    scratch_stack_.clear();
    scratch_stack_.push_back(top);
    while (!scratch_stack_.empty()) {
        const uint32_t n = scratch_stack_.back();
        scratch_stack_.pop_back();
        for (uint32_t o = nodes_[n].first_object; o != kNone; o = object_next_[o]) {
            const Aabb& box = object_box_[o];
            if (isPlaceable(box) && contains(nodes_[top].loose_cell, box)) {
                scratch_objects_.push_back(o);
            }
        }
        if (!nodes_[n].isLeaf()) {
            scratch_stack_.push_back(nodes_[n].child[0]);
            scratch_stack_.push_back(nodes_[n].child[1]);
        }
    }
    for (uint32_t o : scratch_objects_) unlink(o);
    freeDescendants(top);
    std::sort(scratch_objects_.begin(), scratch_objects_.end());  // independent of list order

    scratch_nodes_.clear();
    TreeBuilder builder(nodes_, object_box_, options_, object_node_, build_scratch_,
                        [this](uint32_t parent) {
                            const uint32_t slot = allocateSlot(parent);
                            scratch_nodes_.push_back(slot);
                            return slot;
                        });
    builder.buildSubtree(top, scratch_objects_);
    // Descending object order leaves every list ascending, as after build().
    std::sort(scratch_objects_.begin(), scratch_objects_.end());
    for (size_t k = scratch_objects_.size(); k-- > 0;) {
        link(scratch_objects_[k], object_node_[scratch_objects_[k]]);
    }

    // New nodes: children have larger indices than parents, so descending order fits children
    // first. The top's bounds and count are those of the same objects as before.
    std::sort(scratch_nodes_.begin(), scratch_nodes_.end(), std::greater<uint32_t>());
    for (uint32_t m : scratch_nodes_) computeBounds(m);
    computeBounds(top);
    ++stats_.splits;
    stats_.nodes_created += scratch_nodes_.size();
    ++structure_version_;
}

bool BspTree::canSplit(uint32_t leaf) {
    const BspNode& node = nodes_[leaf];
    if (node.depth >= options_.max_depth) return false;
    scratch_objects_.clear();
    for (uint32_t o = node.first_object; o != kNone; o = object_next_[o]) {
        const Aabb& box = object_box_[o];
        if (isPlaceable(box) && contains(node.loose_cell, box)) scratch_objects_.push_back(o);
    }
    std::sort(scratch_objects_.begin(), scratch_objects_.end());
    TreeBuilder builder(nodes_, object_box_, options_, object_node_, build_scratch_,
                        [](uint32_t) -> uint32_t { return kNone; });
    return builder.wouldSplit(leaf, scratch_objects_);
}

void BspTree::freeDescendants(uint32_t n) {
    if (nodes_[n].isLeaf()) return;
    const uint32_t children[2] = {nodes_[n].child[0], nodes_[n].child[1]};
    nodes_[n].child[0] = kNone;
    nodes_[n].child[1] = kNone;
    for (uint32_t child : children) {
        freeDescendants(child);
        freeSlot(child);
    }
}

void BspTree::mergeChildren(uint32_t n) {
    for (uint32_t side = 0; side < 2; ++side) {
        const uint32_t child = nodes_[n].child[side];
        while (nodes_[child].first_object != kNone) {
            const uint32_t o = nodes_[child].first_object;
            unlink(o);
            link(o, n);
        }
    }
    const uint32_t below = nodes_[n].child[0];
    const uint32_t above = nodes_[n].child[1];
    nodes_[n].child[0] = kNone;
    nodes_[n].child[1] = kNone;
    freeSlot(above);
    freeSlot(below);
    ++stats_.merges;
    ++structure_version_;
}

}  // namespace occsim
