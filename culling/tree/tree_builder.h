// Builds BSP subtrees: the whole tree in BspTree::build(), one crowded leaf's subtree in a local
// split while the tree adapts. Internal to the tree (bsp_tree.cpp, bsp_adaptation.cpp).
#pragma once

#include <algorithm>
#include <functional>
#include <span>
#include <vector>

#include "culling/tree/loose_cells.h"

namespace occsim::bsp_detail {

// Candidate split planes per axis for the surface area heuristic: evenly spaced planes (plus the
// median centre). Each is judged by an exact count of where the placement rule sends every
// object, O(n) per plane, so a node costs O(n) per axis and the build O(n log n) overall.
inline constexpr int kSahCandidatesPerAxis = 32;
// What the surface area heuristic charges for an object a plane leaves in the node, relative to
// one its child takes. The heuristic looks one level down and so underrates going deeper: a
// child's objects end up in leaves far smaller than the child's bounds, while a straddler stays
// at this level for good and is drawn whenever this node is visible. At 1, the heuristic leaves
// 9% of the default scenario's teapots in inner nodes; at 2, none (docs/bsp-tree.md).
inline constexpr float kStraddlerWeight = 2.0f;
// A split plane stays at least this fraction of the cell's extent away from the cell's faces, so
// children never become slivers that float precision cannot split again.
inline constexpr float kMinSplitInset = 1e-3f;
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
            if (side == 0)
                ++counts.below;
            else if (side == 1)
                ++counts.above;
            else
                ++counts.straddling;
        }
        return counts.separates();
    }

  private:
    struct ChildCells {
        Aabb cell[2];  // below, above the plane
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

}  // namespace occsim::bsp_detail
