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

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace occsim {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Candidate split planes per axis for the surface area heuristic: evenly spaced planes (plus the
// median centre). Each is judged by an exact count of where the placement rule sends every
// object, O(n) per plane, so a node costs O(n) per axis and the build O(n log n) overall.
constexpr int kSahCandidatesPerAxis = 32;
// What the surface area heuristic charges for an object a plane leaves in the node, relative to
// one its child takes. The heuristic looks one level down and so underrates going deeper: a
// child's objects end up in leaves far smaller than the child's bounds, while a straddler stays
// at this level for good and is drawn whenever this node is visible. At 1, the heuristic leaves
// 9% of the default scenario's teapots in inner nodes; at 2, none (docs/bsp-tree.md).
constexpr float kStraddlerWeight = 2.0f;
// A split plane stays at least this fraction of the cell's extent away from the cell's faces, so
// children never become slivers that float precision cannot split again.
constexpr float kMinSplitInset = 1e-3f;
// When the root cell grows, it grows past the box by this fraction of its extent, so that a mover
// drifting outwards makes the root grow geometrically often, not every frame.
constexpr float kRootGrowthSlack = 0.25f;

Aabb infiniteAabb() { return Aabb{glm::vec3(-kInfinity), glm::vec3(kInfinity)}; }

bool isPlaceable(const Aabb& box) { return isFiniteAndOrdered(box); }

float surfaceArea(glm::vec3 size) {
    return 2.0f * (size.x * size.y + size.y * size.z + size.z * size.x);
}

// The loose cells (Ulrich's loose octree, adapted to kD splits). The root's loose cell is its cell
// grown on each side by `looseness` times its extent along each axis. A child inherits its
// parent's margins except along the split axis, where both children get the same margin: the
// looseness times the larger child's extent there, but never more than the parent's margin. So
// a child's loose cell lies inside its parent's (ancestors' loose cells nest), and since the two
// siblings' loose cells differ only along the split axis, where they have the same margin, a box
// whose centre lies on one side and which that side's loose cell does not contain is not
// contained by the other side's either (it would have to be narrower than the margin on one side
// of its centre and wider on the other).
Aabb rootLooseCell(const Aabb& cell, float looseness) {
    const glm::vec3 margin = looseness * extent(cell);
    return Aabb{cell.min - margin, cell.max + margin};
}

// The margin both children of `parent` get along `axis` when it is split at `position`.
float childMargin(const BspNode& parent, int axis, float position, float looseness) {
    const float parent_margin = std::min(parent.cell.min[axis] - parent.loose_cell.min[axis],
                                         parent.loose_cell.max[axis] - parent.cell.max[axis]);
    const float larger = std::max(position - parent.cell.min[axis],
                                  parent.cell.max[axis] - position);
    return std::max(0.0f, std::min(parent_margin, looseness * larger));
}

// Clamped to the parent's loose cell, so that nesting survives float rounding exactly (the
// clamp moves only the outer faces, which keeps the siblings' shared margin at the plane).
Aabb childLooseCell(const BspNode& parent, const Aabb& child_cell, int axis, float margin) {
    Aabb loose = parent.loose_cell;
    loose.min[axis] = std::max(child_cell.min[axis] - margin, parent.loose_cell.min[axis]);
    loose.max[axis] = std::min(child_cell.max[axis] + margin, parent.loose_cell.max[axis]);
    return loose;
}

// The box centre every placement decision uses (one formula, so that a build, a split and a
// reinsert round it alike; halving first cannot overflow).
glm::vec3 centreOf(const Aabb& box) { return 0.5f * box.min + 0.5f * box.max; }

// The placement rule, shared by build, local splits and reinsert: a box goes to the child on its
// centre's side of the split (a centre on the plane counts as below) if that child's loose cell
// contains it, else it stays (-1). The centre's path from the root is fixed, so an object's node
// is the deepest node on that path whose loose cell contains its box.
int takingSide(const Aabb& loose_below, const Aabb& loose_above, int axis, float split,
               const Aabb& box) {
    const float centre = centreOf(box)[axis];
    if (centre <= split) return contains(loose_below, box) ? 0 : -1;
    return contains(loose_above, box) ? 1 : -1;
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

// Where the objects of a cell go when it is split: to a child by takingSide(), or straddling
// (they stay in the node).
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

// Builds subtrees: the whole tree in build(), one crowded leaf's subtree in a local split. Nodes
// come from `allocate(parent)`, which returns an initialised slot whose index exceeds the
// parent's; the builder fills in the cell and links it to its parent.
class TreeBuilder {
public:
    using Allocate = std::function<uint32_t(uint32_t parent)>;

    TreeBuilder(std::vector<BspNode>& nodes, std::span<const Aabb> boxes,
                const BspBuildOptions& options, std::vector<uint32_t>& object_node,
                BspBuildScratch& scratch, Allocate allocate)
        : nodes_(nodes),
          boxes_(boxes),
          options_(options),
          object_node_(object_node),
          allocate_(std::move(allocate)),
          centres_(scratch.centres),
          candidates_(scratch.candidates),
          sorted_(scratch.sorted) {}

    // Builds the subtree under `node`, a leaf whose loose cell contains every box in `objects`,
    // and records each object's node.
    void buildSubtree(uint32_t node, std::span<uint32_t> objects) {
        const SplitPlane plane = chooseSplit(node, objects);
        if (!plane.valid) {
            placeAll(node, objects);
            return;
        }

        const ChildCells children_cells = childCells(node, plane);
        // Partition by the placement rule itself: exactly what reinsert() does later.
        auto side = [&](uint32_t object) {
            return takingSide(children_cells.loose[0], children_cells.loose[1], plane.axis,
                              plane.position, boxes_[object]);
        };
        auto below_end = std::partition(objects.begin(), objects.end(),
                                        [&](uint32_t object) { return side(object) == 0; });
        auto above_end = std::partition(below_end, objects.end(),
                                        [&](uint32_t object) { return side(object) == 1; });
        const SideCounts counts{static_cast<uint32_t>(below_end - objects.begin()),
                                static_cast<uint32_t>(above_end - below_end),
                                static_cast<uint32_t>(objects.end() - above_end)};
        if (!counts.separates()) {
            placeAll(node, objects);
            return;
        }
        placeAll(node, std::span<uint32_t>(above_end, objects.end()));  // straddlers stay here

        const uint32_t below_child = allocate_(node);
        const uint32_t above_child = allocate_(node);
        const uint32_t child_depth = nodes_[node].depth + 1;
        const uint32_t children[2] = {below_child, above_child};
        for (int c = 0; c < 2; ++c) {
            BspNode& child = nodes_[children[c]];  // taken after allocation, which may reallocate
            child.cell = children_cells.cell[c];
            child.loose_cell = children_cells.loose[c];
            child.parent = node;
            child.depth = child_depth;
        }
        BspNode& parent = nodes_[node];
        parent.child[0] = below_child;
        parent.child[1] = above_child;
        parent.axis = plane.axis;
        parent.split = plane.position;

        buildSubtree(below_child, std::span<uint32_t>(objects.begin(), below_end));
        buildSubtree(above_child, std::span<uint32_t>(below_end, above_end));
    }

    // Whether buildSubtree() would split `node` (a leaf) over these objects, without changing
    // anything.
    bool wouldSplit(uint32_t node, std::span<uint32_t> objects) {
        const SplitPlane plane = chooseSplit(node, objects);
        if (!plane.valid) return false;
        const ChildCells children_cells = childCells(node, plane);
        SideCounts counts;
        for (uint32_t object : objects) {
            const int side = takingSide(children_cells.loose[0], children_cells.loose[1],
                                        plane.axis, plane.position, boxes_[object]);
            if (side == 0) ++counts.below;
            else if (side == 1) ++counts.above;
            else ++counts.straddling;
        }
        return counts.separates();
    }

private:
    struct ChildCells {
        Aabb cell[2];   // below, above the plane
        Aabb loose[2];
    };

    // The cells and loose cells the children of `node` get when it is split at `plane`.
    ChildCells childCells(uint32_t node, const SplitPlane& plane) const {
        const BspNode& parent = nodes_[node];
        ChildCells out;
        out.cell[0] = parent.cell;
        out.cell[1] = parent.cell;
        out.cell[0].max[plane.axis] = plane.position;
        out.cell[1].min[plane.axis] = plane.position;
        const float margin = childMargin(parent, plane.axis, plane.position, options_.looseness);
        for (int c = 0; c < 2; ++c) {
            out.loose[c] = childLooseCell(parent, out.cell[c], plane.axis, margin);
        }
        return out;
    }

    SplitPlane chooseSplit(uint32_t node, std::span<const uint32_t> objects) {
        if (nodes_[node].depth >= options_.max_depth) return {};
        if (objects.size() <= options_.max_objects_per_leaf) return {};
        const Aabb cell = nodes_[node].cell;
        return options_.split_rule == BspSplitRule::Sah ? chooseSahSplit(nodes_[node], objects)
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
        for (uint32_t object : objects) centres_.push_back(centreOf(boxes_[object])[axis]);
        auto median = centres_.begin() + static_cast<std::ptrdiff_t>(centres_.size() / 2);
        std::nth_element(centres_.begin(), median, centres_.end());
        return planeInside(cell, axis, *median);
    }

    // Surface area heuristic: the probability that a view ray entering a box also enters a box
    // inside it is proportional to the ratio of their surface areas. What a culler queries and
    // draws is the children's bounds (tight over their objects), not their cells, so the cost of
    // a plane is that of the bounds of the objects each side would really take: straddlers stay
    // here and cost a visit of this node each, the others cost a visit of their child's bounds.
    // The sides are those of the placement rule itself (loose cells, the centre's side or
    // nothing): with plain containment the heuristic would favour planes on object faces that
    // loose placement does not need, and could choose a sliver child that takes nothing.
    SplitPlane chooseSahSplit(const BspNode& node, std::span<const uint32_t> objects) {
        const Aabb& cell = node.cell;
        const glm::vec3 size = extent(cell);
        Aabb all;
        for (uint32_t object : objects) extend(all, boxes_[object]);
        const float all_area = std::max(surfaceArea(extent(all)), 1e-30f);
        SplitPlane best;
        float best_cost = kInfinity;
        for (uint8_t axis = 0; axis < 3; ++axis) {
            // Only this axis decides: on the others both children's loose cells equal the
            // parent's, which contains every object here.
            centres_.clear();
            for (uint32_t object : objects) centres_.push_back(centreOf(boxes_[object])[axis]);
            candidates_.clear();
            for (int k = 1; k <= kSahCandidatesPerAxis; ++k) {
                const float fraction = static_cast<float>(k) / (kSahCandidatesPerAxis + 1);
                candidates_.push_back(cell.min[axis] + fraction * size[axis]);
            }
            // The median centre too: the balanced split is always on the table.
            sorted_.assign(centres_.begin(), centres_.end());
            auto median = sorted_.begin() + static_cast<std::ptrdiff_t>(sorted_.size() / 2);
            std::nth_element(sorted_.begin(), median, sorted_.end());
            candidates_.push_back(*median);

            for (float wanted : candidates_) {
                const SplitPlane plane = planeInside(cell, axis, wanted);
                if (!plane.valid) continue;
                const float s = plane.position;
                const float margin = childMargin(node, axis, s, options_.looseness);
                const float below_low = cell.min[axis] - margin;
                const float below_high = s + margin;
                const float above_low = s - margin;
                const float above_high = cell.max[axis] + margin;
                SideCounts counts;
                Aabb below_bounds, above_bounds;
                for (size_t i = 0; i < objects.size(); ++i) {
                    const Aabb& box = boxes_[objects[i]];
                    if (centres_[i] <= s) {  // as takingSide(): the centre's side or nothing
                        if (below_low <= box.min[axis] && box.max[axis] <= below_high) {
                            ++counts.below;
                            extend(below_bounds, box);
                        } else {
                            ++counts.straddling;
                        }
                    } else if (above_low <= box.min[axis] && box.max[axis] <= above_high) {
                        ++counts.above;
                        extend(above_bounds, box);
                    } else {
                        ++counts.straddling;
                    }
                }
                if (!counts.separates()) continue;

                const float below_area = counts.below ? surfaceArea(extent(below_bounds)) : 0.0f;
                const float above_area = counts.above ? surfaceArea(extent(above_bounds)) : 0.0f;
                const float cost = kStraddlerWeight * static_cast<float>(counts.straddling) +
                                   (below_area * static_cast<float>(counts.below) +
                                    above_area * static_cast<float>(counts.above)) /
                                       all_area;
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
    Allocate allocate_;
    // The tree's scratch (BspBuildScratch), reused across nodes and across builders.
    std::vector<float>& centres_;     // for the median
    std::vector<float>& candidates_;  // SAH candidate plane positions along one axis
    std::vector<float>& sorted_;      // centres reordered by nth_element
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
    const int side = takingSide(nodes_[node.child[0]].loose_cell,
                                nodes_[node.child[1]].loose_cell, node.axis, node.split, box);
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
    const float cap = options_.max_root_growth *
                      std::max(built_size.x, std::max(built_size.y, built_size.z));
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
