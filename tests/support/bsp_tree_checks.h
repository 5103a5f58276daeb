// Checks of the BspTree contract (occsim/culling/tree/bsp_tree.h) recomputed from scratch, and the
// random scenes the tree tests share (test_bsp_tree.cpp, test_bsp_tree_moves.cpp,
// test_bsp_adaptation.cpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "occsim/culling/tree/bsp_tree.h"

namespace occsim::testing {

constexpr uint32_t kNone = BspTree::kNone;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

// The split rule as a test name says it.
inline const char* ruleName(BspSplitRule rule) {
    return rule == BspSplitRule::Sah ? "Sah" : "Median";
}

inline bool sameBox(const Aabb& a, const Aabb& b) {
    return a.min.x == b.min.x && a.min.y == b.min.y && a.min.z == b.min.z && a.max.x == b.max.x &&
           a.max.y == b.max.y && a.max.z == b.max.z;
}

inline bool isInfiniteBox(const Aabb& b) {
    return sameBox(b, makeAabb(glm::vec3(-kInf), glm::vec3(kInf)));
}

inline ::testing::Message describe(const Aabb& b) {
    return ::testing::Message() << "[(" << b.min.x << ", " << b.min.y << ", " << b.min.z << ") .. ("
                                << b.max.x << ", " << b.max.y << ", " << b.max.z << ")]";
}

inline Aabb translated(const Aabb& b, glm::vec3 by) { return makeAabb(b.min + by, b.max + by); }

// The placement rule stated independently of the tree's walks: from the root, follow the box
// centre (a centre on a split plane goes below) while the child's loose cell contains the box.
// Boxes that are not finite, or that the root's loose cell does not contain, stay in the root.
inline uint32_t placementByRule(const BspTree& tree, const Aabb& box) {
    uint32_t n = tree.root();
    if (!isFiniteAndOrdered(box) || !contains(tree.node(n).loose_cell, box)) return n;
    const glm::vec3 centre = 0.5f * box.min + 0.5f * box.max;
    while (!tree.node(n).isLeaf()) {
        const BspNode& node = tree.node(n);
        const uint32_t child = node.child[centre[node.axis] <= node.split ? 0 : 1];
        if (!contains(tree.node(child).loose_cell, box)) break;
        n = child;
    }
    return n;
}

inline std::vector<uint32_t> ancestorsAndSelf(const BspTree& tree, uint32_t node) {
    std::vector<uint32_t> path;
    for (uint32_t n = node; n != kNone; n = tree.node(n).parent) path.push_back(n);
    return path;
}

// The checks below recompute each documented invariant of a tree whose bounds have been
// refitted from the object boxes. Each stops at its first fatal failure, and
// expectTreeInvariants() stops at the first checker that had one, so that a broken tree gives
// one readable message rather than a crash in the next walk.

// The root: live, without a parent, at depth 0, its loose cell around its cell.
inline void expectRootInvariants(const BspTree& tree) {
    ASSERT_GE(tree.nodeCount(), 1u);
    const BspNode& root = tree.node(tree.root());
    ASSERT_TRUE(root.live);
    EXPECT_EQ(root.parent, kNone);
    EXPECT_EQ(root.depth, 0u);
    ASSERT_TRUE(contains(root.loose_cell, root.cell));
}

// A freed slot holds nothing and nothing refers to it.
inline void expectFreedSlotEmpty(const BspTree& tree, uint32_t n) {
    const BspNode& node = tree.node(n);
    ASSERT_NE(n, tree.root());
    ASSERT_EQ(node.parent, kNone) << "freed slot " << n;
    ASSERT_TRUE(node.isLeaf()) << "freed slot " << n;
    ASSERT_EQ(node.first_object, kNone) << "freed slot " << n;
    ASSERT_EQ(node.object_count, 0u) << "freed slot " << n;
    ASSERT_TRUE(isEmpty(node.bounds)) << "freed slot " << n;
}

// A live node's links: refitted, both children or none, a live parent of smaller index whose
// child it is, one level deeper, loose cells nested; children of larger index that name it as
// their parent (each counted in `referenced`).
inline void expectLinksOf(const BspTree& tree, uint32_t n, std::vector<int>& referenced) {
    const BspNode& node = tree.node(n);
    ASSERT_FALSE(node.bounds_dirty) << "node " << n << " still dirty after refit";
    ASSERT_EQ(node.child[0] == kNone, node.child[1] == kNone) << "node " << n;
    if (n != tree.root()) {
        ASSERT_LT(node.parent, n) << "parent index must be smaller than the child's";
        const BspNode& parent = tree.node(node.parent);
        ASSERT_TRUE(parent.live) << "node " << n << " has a freed parent";
        ASSERT_TRUE(parent.child[0] == n || parent.child[1] == n)
            << "node " << n << " is not a child of its parent " << node.parent;
        ASSERT_EQ(node.depth, parent.depth + 1) << "node " << n;
        // Loose cells nest.
        ASSERT_TRUE(contains(parent.loose_cell, node.loose_cell)) << "node " << n;
    }
    ASSERT_TRUE(contains(node.loose_cell, node.cell)) << "node " << n;
    if (node.isLeaf()) return;
    for (int side = 0; side < 2; ++side) {
        const uint32_t c = node.child[side];
        ASSERT_GT(c, n) << "child index must be larger than the parent's";
        ASSERT_LT(c, tree.nodeCount());
        ASSERT_TRUE(tree.node(c).live) << "child " << c << " of node " << n << " is freed";
        ASSERT_EQ(tree.node(c).parent, n) << "child " << c << " of node " << n;
        ++referenced[c];
    }
}

// An inner node's children split its cell at `split` along `axis`, strictly inside it, and their
// loose cells are the parent's on the other axes, with the same margin at the plane.
inline void expectSplitOf(const BspTree& tree, uint32_t n) {
    const BspNode& node = tree.node(n);
    const Aabb& cell = node.cell;
    const int axis = node.axis;
    ASSERT_LT(axis, 3);
    ASSERT_GT(node.split, cell.min[axis]) << "node " << n;
    ASSERT_LT(node.split, cell.max[axis]) << "node " << n;
    Aabb below = cell;
    Aabb above = cell;
    below.max[axis] = node.split;
    above.min[axis] = node.split;
    const BspNode& below_child = tree.node(node.child[0]);
    const BspNode& above_child = tree.node(node.child[1]);
    EXPECT_TRUE(sameBox(below_child.cell, below)) << "node " << n;
    EXPECT_TRUE(sameBox(above_child.cell, above)) << "node " << n;
    for (int other = 0; other < 3; ++other) {
        if (other == axis) continue;
        for (const BspNode* child : {&below_child, &above_child}) {
            EXPECT_EQ(child->loose_cell.min[other], node.loose_cell.min[other]) << "node " << n;
            EXPECT_EQ(child->loose_cell.max[other], node.loose_cell.max[other]) << "node " << n;
        }
    }
    // (Equal up to the rounding of split +- margin.)
    const float below_margin = below_child.loose_cell.max[axis] - node.split;
    const float above_margin = node.split - above_child.loose_cell.min[axis];
    EXPECT_NEAR(below_margin, above_margin,
                1e-6f * std::max({1.0f, std::fabs(node.split), below_margin}))
        << "node " << n;
}

// Structure: live nodes and freed slots, links and index order, cells and loose cells, the depth
// and live-node count the tree reports, every live node but the root referenced once.
inline void expectStructureInvariants(const BspTree& tree) {
    const uint32_t node_count = tree.nodeCount();
    uint32_t deepest = 0;
    uint32_t live = 0;
    std::vector<int> referenced(node_count, 0);
    for (uint32_t n = 0; n < node_count; ++n) {
        const BspNode& node = tree.node(n);
        ASSERT_EQ(tree.isLive(n), node.live);
        if (!node.live) {
            expectFreedSlotEmpty(tree, n);
            if (::testing::Test::HasFatalFailure()) return;
            continue;
        }
        ++live;
        deepest = std::max(deepest, node.depth);
        expectLinksOf(tree, n, referenced);
        if (::testing::Test::HasFatalFailure()) return;
        if (node.isLeaf()) continue;
        expectSplitOf(tree, n);
        if (::testing::Test::HasFatalFailure()) return;
    }
    EXPECT_EQ(tree.maxDepth(), deepest);
    EXPECT_EQ(tree.liveNodeCount(), live);
    for (uint32_t n = 1; n < node_count; ++n) {
        if (tree.isLive(n)) {
            ASSERT_EQ(referenced[n], 1) << "node " << n;
        }
    }
}

// Lists: every object in exactly one list, nodeOf() and object_count agree.
inline void expectListInvariants(const BspTree& tree) {
    const uint32_t object_count = tree.objectCount();
    std::vector<int> times_listed(object_count, 0);
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        uint32_t listed = 0;
        for (uint32_t o = tree.firstObject(n); o != kNone; o = tree.nextObject(o)) {
            ASSERT_LT(o, object_count) << "node " << n << " lists a bad object index";
            ASSERT_LE(++listed, object_count) << "node " << n << "'s list has a cycle";
            ++times_listed[o];
            ASSERT_EQ(tree.nodeOf(o), n) << "object " << o << " is listed in node " << n;
        }
        ASSERT_EQ(listed, tree.node(n).object_count) << "node " << n;
    }
    for (uint32_t o = 0; o < object_count; ++o) {
        ASSERT_EQ(times_listed[o], 1)
            << "object " << o << " listed " << times_listed[o] << " times";
    }
}

// Placement: where the rule puts the box, whatever the history; and the local form of the rule
// (the node's loose cell contains the box, no child's loose cell does).
inline void expectPlacementInvariants(const BspTree& tree) {
    const BspNode& root = tree.node(tree.root());
    for (uint32_t o = 0; o < tree.objectCount(); ++o) {
        const Aabb& box = tree.objectBox(o);
        const uint32_t n = tree.nodeOf(o);
        ASSERT_EQ(n, placementByRule(tree, box)) << "object " << o << " " << describe(box);
        if (n == tree.root() && (!isFiniteAndOrdered(box) || !contains(root.loose_cell, box))) {
            continue;
        }
        const BspNode& node = tree.node(n);
        ASSERT_TRUE(contains(node.loose_cell, box))
            << "object " << o << " " << describe(box) << " is in node " << n
            << " whose loose cell does not contain it";
        if (!node.isLeaf()) {
            for (uint32_t c : node.child) {
                ASSERT_FALSE(contains(tree.node(c).loose_cell, box))
                    << "object " << o << " " << describe(box) << " sits in node " << n
                    << " but child " << c << "'s loose cell contains it";
            }
        }
    }
}

// Bounds: tight union of own boxes and children's bounds, infinite over non-finite boxes;
// subtree object counts.
inline void expectBoundsInvariants(const BspTree& tree) {
    const uint32_t node_count = tree.nodeCount();
    std::vector<Aabb> expected(node_count);
    std::vector<uint32_t> expected_count(node_count, 0);
    for (uint32_t n = node_count; n-- > 0;) {
        if (!tree.isLive(n)) continue;
        Aabb b;
        bool infinite = false;
        for (uint32_t o = tree.firstObject(n); o != kNone; o = tree.nextObject(o)) {
            const Aabb& box = tree.objectBox(o);
            if (isFiniteAndOrdered(box)) {
                extend(b, box);
            } else {
                infinite = true;
            }
        }
        const BspNode& node = tree.node(n);
        expected_count[n] = node.object_count;
        if (!node.isLeaf()) {
            for (uint32_t c : node.child) {
                extend(b, expected[c]);
                infinite |= isInfiniteBox(expected[c]);
                expected_count[n] += expected_count[c];
            }
        }
        expected[n] = infinite ? makeAabb(glm::vec3(-kInf), glm::vec3(kInf)) : b;
    }
    for (uint32_t n = 0; n < node_count; ++n) {
        if (!tree.isLive(n)) continue;
        const Aabb& bounds = tree.bounds(n);
        ASSERT_TRUE(sameBox(bounds, expected[n])) << "node " << n << " bounds " << describe(bounds)
                                                  << ", recomputed " << describe(expected[n]);
        ASSERT_EQ(tree.node(n).subtree_object_count, expected_count[n]) << "node " << n;
    }
    EXPECT_EQ(tree.node(tree.root()).subtree_object_count, tree.objectCount());
}

// Every documented invariant: structure (live nodes, freed slots, index order), cells and loose
// cells, lists, placement, bounds and subtree counts.
inline void expectTreeInvariants(const BspTree& tree) {
    for (void (*check)(const BspTree&) :
         {expectRootInvariants, expectStructureInvariants, expectListInvariants,
          expectPlacementInvariants, expectBoundsInvariants}) {
        check(tree);
        if (::testing::Test::HasFatalFailure()) return;
    }
}

// A random scene: boxes of widely varying size, some with zero extent on every axis (points) and
// some flat on one axis.
inline std::vector<Aabb> randomScene(std::mt19937& rng, size_t count, glm::vec3 world_half_size) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_real_distribution<float> log_size(std::log(0.05f), std::log(20.0f));
    std::vector<Aabb> boxes;
    boxes.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        const glm::vec3 centre = world_half_size * glm::vec3(unit(rng), unit(rng), unit(rng));
        glm::vec3 size(std::exp(log_size(rng)), std::exp(log_size(rng)), std::exp(log_size(rng)));
        if (i % 10 == 0) size = glm::vec3(0.0f);                // a point
        if (i % 10 == 1) size[static_cast<int>(i % 3)] = 0.0f;  // flat
        boxes.push_back(makeAabb(centre - 0.5f * size, centre + 0.5f * size));
    }
    return boxes;
}

// A field like the default scenario's: `count` teapot-sized boxes (1 to 2.5 high, 1.5 times as
// wide) in 70 x 8 x 200, densely enough that the classic tree leaves most of them in inner nodes.
inline std::vector<Aabb> teapotField(uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> x(-35, 35), y(0, 8), z(-200, 0), size(1.0f, 2.5f);
    std::vector<Aabb> boxes;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 lo(x(rng), y(rng), z(rng));
        const float s = size(rng);
        boxes.push_back(makeAabb(lo, lo + glm::vec3(1.5f * s, s, 1.5f * s)));
    }
    return boxes;
}

// Objects whose node is an inner node.
inline uint32_t objectsInInnerNodes(const BspTree& tree) {
    uint32_t count = 0;
    for (uint32_t o = 0; o < tree.objectCount(); ++o) {
        count += tree.node(tree.nodeOf(o)).isLeaf() ? 0 : 1;
    }
    return count;
}

}  // namespace occsim::testing
