// The loose cells of the BSP tree and its placement rule (bsp_tree.cpp says why loose cells):
// what the build, the local splits of adaptation and reinsert all decide with, so that they
// decide alike. Internal to the tree (bsp_tree.cpp, bsp_adaptation.cpp, tree_builder.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "occsim/culling/tree/bsp_tree.h"

namespace occsim::bsp_detail {

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

inline Aabb infiniteAabb() { return Aabb{glm::vec3(-kInfinity), glm::vec3(kInfinity)}; }

inline bool isPlaceable(const Aabb& box) { return isFiniteAndOrdered(box); }

inline float surfaceArea(glm::vec3 size) {
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
inline Aabb rootLooseCell(const Aabb& cell, float looseness) {
    const glm::vec3 margin = looseness * extent(cell);
    return Aabb{cell.min - margin, cell.max + margin};
}

// The margin both children of `parent` get along `axis` when it is split at `position`.
inline float childMargin(const BspNode& parent, int axis, float position, float looseness) {
    const float parent_margin = std::min(parent.cell.min[axis] - parent.loose_cell.min[axis],
                                         parent.loose_cell.max[axis] - parent.cell.max[axis]);
    const float larger =
        std::max(position - parent.cell.min[axis], parent.cell.max[axis] - position);
    return std::max(0.0f, std::min(parent_margin, looseness * larger));
}

// Clamped to the parent's loose cell, so that nesting survives float rounding exactly (the
// clamp moves only the outer faces, which keeps the siblings' shared margin at the plane).
inline Aabb childLooseCell(const BspNode& parent, const Aabb& child_cell, int axis, float margin) {
    Aabb loose = parent.loose_cell;
    loose.min[axis] = std::max(child_cell.min[axis] - margin, parent.loose_cell.min[axis]);
    loose.max[axis] = std::min(child_cell.max[axis] + margin, parent.loose_cell.max[axis]);
    return loose;
}

// The box centre every placement decision uses (one formula, so that a build, a split and a
// reinsert round it alike; halving first cannot overflow).
inline glm::vec3 centreOf(const Aabb& box) { return 0.5f * box.min + 0.5f * box.max; }

// The placement rule, shared by build, local splits and reinsert: a box goes to the child on its
// centre's side of the split (a centre on the plane counts as below) if that child's loose cell
// contains it, else it stays (-1). The centre's path from the root is fixed, so an object's node
// is the deepest node on that path whose loose cell contains its box.
inline int takingSide(const Aabb& loose_below, const Aabb& loose_above, int axis, float split,
                      const Aabb& box) {
    const float centre = centreOf(box)[axis];
    if (centre <= split) return contains(loose_below, box) ? 0 : -1;
    return contains(loose_above, box) ? 1 : -1;
}

// The root cell: bounds of the finite boxes, with every axis given a positive size and then
// enlarged by the margin on each side.
inline Aabb rootCellFor(std::span<const Aabb> boxes, float margin) {
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
        const float minimum_size = 1e-3f * std::max(largest, std::max(1.0f, std::fabs(middle)));
        if (scene.max[axis] - scene.min[axis] < minimum_size) {
            scene.min[axis] = middle - 0.5f * minimum_size;
            scene.max[axis] = middle + 0.5f * minimum_size;
        }
    }
    const glm::vec3 grow = margin * extent(scene);
    return Aabb{scene.min - grow, scene.max + grow};
}

}  // namespace occsim::bsp_detail
