// The axis-aligned BSP tree over moving objects declared in bsp_tree.h.
//
// Placement follows Kovalčík & Sochor (2005): the cells are built once, and each object is kept in
// the node that encompasses it "fully and as tightly as possible", i.e. the deepest node whose
// cell contains its box. A moving object is re-placed by walking up from its current node only
// as far as needed and then down again, so small moves touch few nodes, and node bounds are
// refitted lazily (only dirty nodes, children before parents).
//
// Boxes that are not finite and ordered (NaN, infinite, inverted) cannot be placed by
// containment; they live in the root and make their subtree's bounds infinite, so that a culler
// never skips them on the evidence of a box that means nothing.
#include "culling/bsp_tree.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace occsim {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Candidate split planes per axis for the surface area heuristic: evenly spaced planes, plus
// every object face (a plane on a face never cuts that object, so the heuristic finds the gaps
// between objects instead of cutting through them). Side counts for a plane come from binary
// searches over the sorted faces, so all faces cost O(n log n) per axis.
constexpr int kSahCandidatesPerAxis = 8;
// A split plane stays at least this fraction of the cell's extent away from the cell's faces, so
// children never become slivers that float precision cannot split again.
constexpr float kMinSplitInset = 1e-3f;

Aabb infiniteAabb() { return Aabb{glm::vec3(-kInfinity), glm::vec3(kInfinity)}; }

bool isPlaceable(const Aabb& box) { return isFiniteAndOrdered(box); }

float surfaceArea(glm::vec3 size) {
    return 2.0f * (size.x * size.y + size.y * size.z + size.z * size.x);
}

// The root cell: bounds of the finite boxes, with every axis given a positive size and then
// enlarged by the margin on each side.
Aabb rootCellFor(std::span<const Aabb> boxes, float margin) {
    Aabb scene;
    for (const Aabb& box : boxes) {
        if (isPlaceable(box)) extend(scene, box);
    }
    if (isEmpty(scene)) scene = Aabb{glm::vec3(-0.5f), glm::vec3(0.5f)};  // unit cube at origin

    const glm::vec3 size = extent(scene);
    const float largest = std::max(size.x, std::max(size.y, size.z));
    for (int axis = 0; axis < 3; ++axis) {
        // A flat scene (all objects on a plane) would give a zero-thickness cell. The minimum size
        // scales with the coordinates' magnitude so that it survives float rounding far from the
        // origin.
        const float middle = 0.5f * scene.min[axis] + 0.5f * scene.max[axis];
        const float minimum_size =
            1e-3f * std::max(largest, std::max(1.0f, std::fabs(middle)));
        if (scene.max[axis] - scene.min[axis] < minimum_size) {
            scene.min[axis] = middle - 0.5f * minimum_size;
            scene.max[axis] = middle + 0.5f * minimum_size;
        }
    }
    const glm::vec3 grow = margin * extent(scene);
    return Aabb{scene.min - grow, scene.max + grow};
}

struct SplitPlane {
    bool valid = false;
    uint8_t axis = 0;
    float position = 0.0f;
};

// Where the objects of a cell go when it is split: below (max on or under the plane), above (min
// on or over it) or straddling (they stay in the node). The child cells are the parent's cell
// cut at the plane; a box on the plane with zero thickness fits both and goes below, the same
// order reinsert() tries the children in.

struct SideCounts {
    uint32_t below = 0;
    uint32_t above = 0;
    uint32_t straddling = 0;

    // A split is worth making only if the objects do not all end up in the same place.
    bool separates() const {
        const int groups = (below > 0) + (above > 0) + (straddling > 0);
        return groups >= 2;
    }
};

class TreeBuilder {
public:
    TreeBuilder(std::vector<BspNode>& nodes, std::span<const Aabb> boxes,
                const BspBuildOptions& options, std::vector<uint32_t>& object_node)
        : nodes_(nodes), boxes_(boxes), options_(options), object_node_(object_node) {}

    // Builds the subtree under `node`, whose cell contains every box in `objects`, and records
    // each object's node.
    void buildSubtree(uint32_t node, std::span<uint32_t> objects) {
        const SplitPlane plane = chooseSplit(node, objects);
        if (!plane.valid) {
            placeAll(node, objects);
            return;
        }

        Aabb below_cell = nodes_[node].cell;
        Aabb above_cell = nodes_[node].cell;
        below_cell.max[plane.axis] = plane.position;
        above_cell.min[plane.axis] = plane.position;
        // Partition by containment in the actual child cells: exactly the test reinsert() uses.
        auto below_end = std::partition(objects.begin(), objects.end(), [&](uint32_t object) {
            return contains(below_cell, boxes_[object]);
        });
        auto above_end = std::partition(below_end, objects.end(), [&](uint32_t object) {
            return contains(above_cell, boxes_[object]);
        });
        const SideCounts counts{static_cast<uint32_t>(below_end - objects.begin()),
                                static_cast<uint32_t>(above_end - below_end),
                                static_cast<uint32_t>(objects.end() - above_end)};
        if (!counts.separates()) {
            placeAll(node, objects);
            return;
        }
        placeAll(node, std::span<uint32_t>(above_end, objects.end()));  // straddlers stay here

        // Children are allocated when their parent splits, so their indices exceed the parent's.
        const uint32_t below_child = static_cast<uint32_t>(nodes_.size());
        const uint32_t above_child = below_child + 1;
        const uint32_t child_depth = nodes_[node].depth + 1;
        for (const Aabb& cell : {below_cell, above_cell}) {
            BspNode child;
            child.cell = cell;
            child.parent = node;
            child.depth = child_depth;
            nodes_.push_back(child);
        }
        BspNode& parent = nodes_[node];  // taken after push_back, which may reallocate
        parent.child[0] = below_child;
        parent.child[1] = above_child;
        parent.axis = plane.axis;
        parent.split = plane.position;

        buildSubtree(below_child, std::span<uint32_t>(objects.begin(), below_end));
        buildSubtree(above_child, std::span<uint32_t>(below_end, above_end));
    }

private:
    SplitPlane chooseSplit(uint32_t node, std::span<const uint32_t> objects) {
        if (nodes_[node].depth >= options_.max_depth) return {};
        if (objects.size() <= options_.max_objects_per_leaf) return {};
        const Aabb cell = nodes_[node].cell;
        return options_.split_rule == BspSplitRule::Sah ? chooseSahSplit(cell, objects)
                                                        : chooseMedianSplit(cell, objects);
    }

    // The plane at `wanted` moved at least kMinSplitInset of the extent inside the cell; invalid
    // when the cell is too thin for float precision to put a plane strictly inside.
    static SplitPlane planeInside(const Aabb& cell, uint8_t axis, float wanted) {
        const float low = cell.min[axis];
        const float high = cell.max[axis];
        const float inset = kMinSplitInset * (high - low);
        const float position = std::clamp(wanted, low + inset, high - inset);
        SplitPlane plane;
        plane.valid = low < position && position < high;
        plane.axis = axis;
        plane.position = position;
        return plane;
    }

    // Longest axis of the cell, at the median of the object centres along it.
    SplitPlane chooseMedianSplit(const Aabb& cell, std::span<const uint32_t> objects) {
        const glm::vec3 size = extent(cell);
        uint8_t axis = 0;
        if (size.y > size[axis]) axis = 1;
        if (size.z > size[axis]) axis = 2;

        centres_.clear();
        for (uint32_t object : objects) {
            const Aabb& box = boxes_[object];
            centres_.push_back(0.5f * box.min[axis] + 0.5f * box.max[axis]);
        }
        auto median = centres_.begin() + static_cast<std::ptrdiff_t>(centres_.size() / 2);
        std::nth_element(centres_.begin(), median, centres_.end());
        return planeInside(cell, axis, *median);
    }

    // Surface area heuristic: the probability that a ray (or view) entering the cell also enters
    // a child is proportional to the child's surface area. Objects below a child are tested only
    // when that child is visited; straddlers stay in this node and are tested whenever it is.
    SplitPlane chooseSahSplit(const Aabb& cell, std::span<const uint32_t> objects) {
        const glm::vec3 size = extent(cell);
        const float cell_area = surfaceArea(size);
        const auto n = static_cast<uint32_t>(objects.size());
        SplitPlane best;
        float best_cost = kInfinity;
        for (uint8_t axis = 0; axis < 3; ++axis) {
            mins_.clear();
            maxs_.clear();
            for (uint32_t object : objects) {
                mins_.push_back(boxes_[object].min[axis]);
                maxs_.push_back(boxes_[object].max[axis]);
            }
            std::sort(mins_.begin(), mins_.end());
            std::sort(maxs_.begin(), maxs_.end());
            candidates_.assign(mins_.begin(), mins_.end());
            candidates_.insert(candidates_.end(), maxs_.begin(), maxs_.end());
            for (int k = 1; k <= kSahCandidatesPerAxis; ++k) {
                const float fraction = static_cast<float>(k) / (kSahCandidatesPerAxis + 1);
                candidates_.push_back(cell.min[axis] + fraction * size[axis]);
            }
            for (float wanted : candidates_) {
                const SplitPlane plane = planeInside(cell, axis, wanted);
                if (!plane.valid) continue;
                // Closed containment: a box whose max lies on the plane fits below, one whose
                // min lies on it fits above.
                SideCounts counts;
                counts.below = static_cast<uint32_t>(
                    std::upper_bound(maxs_.begin(), maxs_.end(), plane.position) - maxs_.begin());
                counts.above = static_cast<uint32_t>(
                    mins_.end() - std::lower_bound(mins_.begin(), mins_.end(), plane.position));
                // A box with min == max == plane would count on both sides: it goes below.
                if (counts.below + counts.above > n) counts.above = n - counts.below;
                counts.straddling = n - counts.below - counts.above;
                if (!counts.separates()) continue;

                glm::vec3 below_size = size;
                below_size[axis] = plane.position - cell.min[axis];
                glm::vec3 above_size = size;
                above_size[axis] = cell.max[axis] - plane.position;
                const float cost = static_cast<float>(counts.straddling) +
                                   (surfaceArea(below_size) * static_cast<float>(counts.below) +
                                    surfaceArea(above_size) * static_cast<float>(counts.above)) /
                                       cell_area;
                if (cost < best_cost) {
                    best_cost = cost;
                    best = plane;
                }
            }
        }
        return best;
    }

    void placeAll(uint32_t node, std::span<const uint32_t> objects) {
        for (uint32_t object : objects) object_node_[object] = node;
    }

    std::vector<BspNode>& nodes_;
    std::span<const Aabb> boxes_;
    const BspBuildOptions& options_;
    std::vector<uint32_t>& object_node_;
    std::vector<float> centres_;     // scratch for the median, reused across nodes
    std::vector<float> candidates_;  // scratch: SAH candidate plane positions along one axis
    std::vector<float> mins_, maxs_; // scratch: sorted object faces along one axis
};

}  // namespace

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
    return true;
}

void BspTree::build(std::span<const Aabb> object_boxes, const BspBuildOptions& options) {
    assert(options.isValid(nullptr));
    assert(object_boxes.size() < kNone);
    const auto object_count = static_cast<uint32_t>(object_boxes.size());

    object_box_.assign(object_boxes.begin(), object_boxes.end());
    object_node_.assign(object_count, root());
    object_next_.assign(object_count, kNone);
    object_prev_.assign(object_count, kNone);

    nodes_.clear();
    BspNode root_node;
    root_node.cell = rootCellFor(object_boxes, options.root_margin);
    nodes_.push_back(root_node);

    // Only boxes inside the root cell take part in splitting; the rest stay in the root.
    std::vector<uint32_t> placeable;
    placeable.reserve(object_count);
    for (uint32_t object = 0; object < object_count; ++object) {
        const Aabb& box = object_box_[object];
        if (isPlaceable(box) && contains(nodes_[0].cell, box)) placeable.push_back(object);
    }
    TreeBuilder builder(nodes_, object_box_, options, object_node_);
    builder.buildSubtree(root(), placeable);

    // Linking in descending order leaves every node's list in ascending object order.
    for (uint32_t object = object_count; object-- > 0;) link(object, object_node_[object]);

    // Every node may be dirty at most once between refits, so this is all the list ever needs.
    dirty_nodes_.clear();
    dirty_nodes_.reserve(nodes_.size());
    for (uint32_t n = nodeCount(); n-- > 0;) {
        dirty_nodes_.push_back(n);
        nodes_[n].bounds_dirty = true;
    }
    const uint64_t refit_before = stats_.nodes_refit;
    refitDirtyBounds();
    stats_.nodes_refit = refit_before;  // the initial fit is part of build, not a refit

    // A new structure: every slot holds a new node.
    for (BspNode& node : nodes_) node.generation = next_generation_++;
    ++structure_version_;
}

void BspTree::reinsert(uint32_t object, const Aabb& new_box) {
    assert(object < objectCount());
    ++stats_.reinserts;
    object_box_[object] = new_box;

    const uint32_t old_node = object_node_[object];
    const uint32_t new_node = findDeepestContaining(old_node, new_box);
    if (new_node != old_node) {
        unlink(object);
        link(object, new_node);
        ++stats_.reinserts_moved;
    }
    // The box changed even if the node did not, so the node's bounds (and its ancestors') must be
    // refitted; the old node's subtree lost the object's old box.
    markDirtyToRoot(old_node);
    markDirtyToRoot(new_node);
}

void BspTree::refitDirtyBounds() {
    // Children have larger indices than parents: descending order refits children first, so a
    // parent reads its children's fresh bounds. std::sort works in place (no allocation).
    std::sort(dirty_nodes_.begin(), dirty_nodes_.end(), std::greater<uint32_t>());
    for (uint32_t n : dirty_nodes_) {
        BspNode& node = nodes_[n];
        Aabb bounds;
        for (uint32_t object = node.first_object; object != kNone; object = object_next_[object]) {
            const Aabb& box = object_box_[object];
            if (!isPlaceable(box)) {
                bounds = infiniteAabb();
                break;  // nothing can widen infinite bounds
            }
            extend(bounds, box);
        }
        for (uint32_t child : node.child) {
            if (child != kNone) extend(bounds, nodes_[child].bounds);
        }
        node.bounds = bounds;
        node.bounds_dirty = false;
    }
    stats_.nodes_refit += dirty_nodes_.size();
    dirty_nodes_.clear();  // keeps its capacity
}

uint32_t BspTree::maxDepth() const {
    uint32_t deepest = 0;
    for (const BspNode& node : nodes_) deepest = std::max(deepest, node.depth);
    return deepest;
}

uint32_t BspTree::findDeepestContaining(uint32_t start, const Aabb& box) {
    if (!isPlaceable(box)) {
        ++stats_.nodes_walked;
        return root();
    }
    // Up: the cells of ancestors nest, so the first one that contains the box is where the
    // descent starts; the root takes whatever leaves its cell.
    uint32_t node = start;
    ++stats_.nodes_walked;
    while (node != root() && !contains(nodes_[node].cell, box)) {
        node = nodes_[node].parent;
        ++stats_.nodes_walked;
    }
    if (!contains(nodes_[node].cell, box)) return node;  // outside the root cell

    // Down: at most one child contains the box unless it lies flat on the split plane; the
    // child below the plane is tried first, as in build().
    while (!nodes_[node].isLeaf()) {
        uint32_t next = kNone;
        for (uint32_t child : nodes_[node].child) {
            if (contains(nodes_[child].cell, box)) {
                next = child;
                break;
            }
        }
        if (next == kNone) break;
        node = next;
        ++stats_.nodes_walked;
    }
    return node;
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
