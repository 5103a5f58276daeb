// BspTree after objects move: thousands of random moves (split planes included) under each split
// rule keep every object where the placement rule puts it; reinsert walks, their counters, dirty
// marking, and a non-finite box that comes and goes. The structural contract is checked from
// scratch (bsp_tree_checks.h); the build itself is in test_bsp_tree.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "bsp_tree_checks.h"

namespace occsim {
namespace {

using testing::ancestorsAndSelf;
using testing::expectTreeInvariants;
using testing::isInfiniteBox;
using testing::kInf;
using testing::kNan;
using testing::kNone;
using testing::placementByRule;
using testing::randomScene;
using testing::ruleName;
using testing::sameBox;
using testing::translated;

// A box touching (or, with zero thickness, lying on) the split plane of a random inner node.
Aabb onRandomSplitPlane(const BspTree& tree, std::mt19937& rng, const Aabb& box) {
    std::vector<uint32_t> inner;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        if (tree.isLive(n) && !tree.node(n).isLeaf()) inner.push_back(n);
    }
    const BspNode& node = tree.node(inner[rng() % inner.size()]);
    const int axis = node.axis;
    // Centred in the node's cell on the other axes so that the box stays inside it.
    const glm::vec3 cell_centre = center(node.cell);
    const glm::vec3 half = 0.25f * glm::min(extent(box), extent(node.cell));
    Aabb out = makeAabb(cell_centre - half, cell_centre + half);
    const float thickness = out.max[axis] - out.min[axis];
    switch (rng() % 3) {
        case 0:  // touching from below
            out.max[axis] = node.split;
            out.min[axis] = std::max(node.split - thickness, node.cell.min[axis]);
            break;
        case 1:  // touching from above
            out.min[axis] = node.split;
            out.max[axis] = std::min(node.split + thickness, node.cell.max[axis]);
            break;
        default:  // zero thickness, on the plane
            out.min[axis] = out.max[axis] = node.split;
            break;
    }
    return out;
}

class BspTreeRandomMoves : public ::testing::TestWithParam<BspSplitRule> {};

TEST_P(BspTreeRandomMoves, EveryObjectSitsWhereThePlacementRulePutsItAfter10000RandomMoves) {
    std::mt19937 rng(GetParam() == BspSplitRule::Sah ? 4242u : 1717u);
    const glm::vec3 world_half_size(100.0f, 40.0f, 70.0f);
    std::vector<Aabb> boxes = randomScene(rng, 2000, world_half_size);

    BspBuildOptions options;
    options.split_rule = GetParam();
    options.max_depth = 16;
    options.max_objects_per_leaf = 4;
    BspTree tree;
    tree.build(boxes, options);
    ASSERT_GT(tree.nodeCount(), 100u) << "the scene should split into many cells";
    expectTreeInvariants(tree);
    if (HasFatalFailure()) return;

    // A few objects on split planes right away.
    for (uint32_t o = 0; o < 50; ++o) {
        boxes[o] = onRandomSplitPlane(tree, rng, boxes[o]);
        tree.reinsert(o, boxes[o]);
    }
    tree.refitDirtyBounds();
    expectTreeInvariants(tree);
    if (HasFatalFailure()) return;

    std::normal_distribution<float> step(0.0f, 1.5f);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<uint32_t> non_finite;  // objects currently holding a non-finite box
    int moved_out_of_root = 0;
    int moved_far_away = 0;
    int made_non_finite = 0;
    int made_finite_again = 0;
    for (int move = 1; move <= 10000; ++move) {
        const uint32_t roll = rng() % 100;
        uint32_t object = rng() % tree.objectCount();
        Aabb box = boxes[object];
        if (!non_finite.empty() && roll < 3) {
            // A non-finite object becomes finite again, somewhere in the world.
            const size_t k = rng() % non_finite.size();
            object = non_finite[k];
            non_finite.erase(non_finite.begin() + static_cast<std::ptrdiff_t>(k));
            const glm::vec3 centre = world_half_size * glm::vec3(unit(rng), unit(rng), unit(rng));
            box = makeAabb(centre - 0.5f, centre + 0.5f);
            ++made_finite_again;
        } else if (!isFiniteAndOrdered(box)) {
            continue;  // leave non-finite objects to the branch above
        } else if (roll < 5) {
            // NaN, infinite or inverted.
            switch (rng() % 3) {
                case 0:
                    box.min.y = kNan;
                    break;
                case 1:
                    box.max.x = kInf;
                    break;
                default:
                    std::swap(box.min.z, box.max.z);
                    box.min.z += 1.0f;
                    break;
            }
            non_finite.push_back(object);
            ++made_non_finite;
        } else if (roll < 9) {
            // Outside the root cell (which grows to take it).
            box = translated(box, glm::vec3(0.0f, 5.0f * world_half_size.y, 0.0f));
            ++moved_out_of_root;
        } else if (roll < 10) {
            // Far beyond any growth: lives in the root.
            box = translated(box, glm::vec3(1e7f, 0.0f, 0.0f));
            ++moved_far_away;
        } else if (roll < 18) {
            // A big jump to anywhere in the world.
            const glm::vec3 centre = world_half_size * glm::vec3(unit(rng), unit(rng), unit(rng));
            box = translated(box, centre - center(box));
        } else if (roll < 24) {
            box = onRandomSplitPlane(tree, rng, box);
        } else {
            // A small random-walk step.
            box = translated(box, glm::vec3(step(rng), step(rng), step(rng)));
        }
        boxes[object] = box;
        tree.reinsert(object, box);

        if (move % 100 == 0) tree.refitDirtyBounds();  // like one refit per frame
        if (move % 2500 == 0) {
            tree.refitDirtyBounds();
            expectTreeInvariants(tree);
            if (HasFatalFailure()) return;
        }
    }
    tree.refitDirtyBounds();
    expectTreeInvariants(tree);
    if (HasFatalFailure()) return;

    // The run must have exercised the interesting cases.
    EXPECT_GT(moved_out_of_root, 100);
    EXPECT_GT(moved_far_away, 20);
    EXPECT_GT(made_non_finite, 50);
    EXPECT_GT(made_finite_again, 20);
    EXPECT_GT(tree.stats().root_growths, 0u);
    EXPECT_GT(tree.stats().splits, 0u);
    EXPECT_GT(tree.stats().merges, 0u);
    for (uint32_t o = 0; o < tree.objectCount(); ++o) {
        EXPECT_TRUE(sameBox(tree.objectBox(o), boxes[o]) || !isFiniteAndOrdered(boxes[o]))
            << "object " << o << " box not stored";
    }
    if (!non_finite.empty()) {
        EXPECT_TRUE(isInfiniteBox(tree.bounds(tree.root())))
            << "a non-finite object must make the root bounds infinite";
    }
}

INSTANTIATE_TEST_SUITE_P(SplitRules, BspTreeRandomMoves,
                         ::testing::Values(BspSplitRule::Median, BspSplitRule::Sah),
                         [](const ::testing::TestParamInfo<BspSplitRule>& param_info) {
                             return std::string(ruleName(param_info.param));
                         });

TEST(BspTree, MedianRuleSplitsTheLongestCellAxisAtTheMedianObjectCentre) {
    // Distinct points in a scene long in x: the root split is on x, and half the points lie on
    // each side of it.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> x(-100.0f, 100.0f);
    std::uniform_real_distribution<float> yz(-10.0f, 10.0f);
    std::vector<Aabb> points;
    for (int i = 0; i < 1001; ++i) {
        const glm::vec3 p(x(rng), yz(rng), yz(rng));
        points.push_back(makeAabb(p, p));
    }
    BspTree tree;
    tree.build(points, BspBuildOptions{});
    const BspNode& root = tree.node(tree.root());
    ASSERT_FALSE(root.isLeaf());
    EXPECT_EQ(root.axis, 0);
    int below = 0;
    int above = 0;
    for (const Aabb& p : points) (p.min.x <= root.split ? below : above)++;
    EXPECT_LE(std::abs(below - above), 2) << "below " << below << ", above " << above;

    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const BspNode& node = tree.node(n);
        if (node.isLeaf()) continue;
        const glm::vec3 size = extent(node.cell);
        EXPECT_EQ(size[node.axis], std::max(size.x, std::max(size.y, size.z)))
            << "node " << n << " did not split its longest axis";
    }
    expectTreeInvariants(tree);
}
// A tree over a random scene for the reinsert tests.
struct SmallWorld {
    std::vector<Aabb> boxes;
    BspTree tree;

    explicit SmallWorld(uint32_t seed, bool adapt = true) {
        std::mt19937 rng(seed);
        boxes = randomScene(rng, 1000, glm::vec3(50.0f));
        BspBuildOptions options;
        options.adapt = adapt;
        tree.build(boxes, options);
    }

    // An object stored in a leaf at depth >= 3 with a box of non-zero size.
    uint32_t deepLeafObject() const {
        for (uint32_t o = 0; o < tree.objectCount(); ++o) {
            const BspNode& node = tree.node(tree.nodeOf(o));
            if (node.isLeaf() && node.depth >= 3 &&
                glm::all(glm::greaterThan(extent(boxes[o]), glm::vec3(0.0f)))) {
                return o;
            }
        }
        return kNone;
    }
};

TEST(BspTree, ReinsertThatStillFitsItsNodeNeedsNoWalk) {
    SmallWorld world(21);
    BspTree& tree = world.tree;
    const uint32_t object = world.deepLeafObject();
    ASSERT_NE(object, kNone);
    const uint32_t node = tree.nodeOf(object);

    // Shrinking the box towards its centre keeps it inside the same loose cell.
    const Aabb& old_box = world.boxes[object];
    const glm::vec3 c = center(old_box);
    const Aabb smaller = makeAabb(glm::mix(old_box.min, c, 0.5f), glm::mix(old_box.max, c, 0.5f));
    const BspStats before = tree.stats();
    tree.reinsert(object, smaller);
    EXPECT_EQ(tree.nodeOf(object), node);
    EXPECT_EQ(tree.stats().reinserts, before.reinserts + 1);
    EXPECT_EQ(tree.stats().reinserts_in_place, before.reinserts_in_place + 1);
    EXPECT_EQ(tree.stats().reinserts_moved, before.reinserts_moved);
    EXPECT_EQ(tree.stats().nodes_walked - before.nodes_walked, 1u) << "only its own node";
    EXPECT_TRUE(sameBox(tree.objectBox(object), smaller));

    // A small move that stays inside the node's loose cell (with the centre in its cell): the
    // same, although the box now pokes out of the cell.
    const BspNode& leaf = tree.node(node);
    const glm::vec3 room = 0.25f * (leaf.loose_cell.max - leaf.cell.max);
    const Aabb nudged = translated(smaller, glm::min(room, leaf.cell.max - center(smaller)));
    ASSERT_EQ(placementByRule(tree, nudged), node);
    tree.reinsert(object, nudged);
    EXPECT_EQ(tree.nodeOf(object), node);
    EXPECT_EQ(tree.stats().reinserts_in_place, before.reinserts_in_place + 2);
    EXPECT_EQ(tree.stats().nodes_walked - before.nodes_walked, 2u);

    tree.refitDirtyBounds();
    expectTreeInvariants(tree);
}

TEST(BspTree, ReinsertWalksUpToTheCommonAncestorAndDownAndCountsEveryNode) {
    // Without adaptation, so that no growth adds walks. Every reinsert walks its start node,
    // then up to the lowest common ancestor of its old and new node, then down.
    SmallWorld world(25, /*adapt=*/false);
    BspTree& tree = world.tree;
    std::mt19937 rng(26);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::normal_distribution<float> step(0.0f, 2.0f);
    uint64_t in_place = 0, moved = 0;
    for (int move = 0; move < 3000; ++move) {
        const uint32_t object = rng() % tree.objectCount();
        const Aabb box =
            rng() % 4 == 0
                ? translated(world.boxes[object],
                             50.0f * glm::vec3(unit(rng), unit(rng), unit(rng)) -
                                 center(world.boxes[object]))
                : translated(world.boxes[object], glm::vec3(step(rng), step(rng), step(rng)));
        const uint32_t start = tree.nodeOf(object);
        const uint32_t target = placementByRule(tree, box);
        const std::vector<uint32_t> up = ancestorsAndSelf(tree, start);
        const std::vector<uint32_t> down = ancestorsAndSelf(tree, target);
        uint32_t common = kNone;
        for (uint32_t n : up) {
            if (std::find(down.begin(), down.end(), n) != down.end()) {
                common = n;
                break;
            }
        }
        ASSERT_NE(common, kNone);
        const uint64_t expected_walk = 1 + (tree.node(start).depth - tree.node(common).depth) +
                                       (tree.node(target).depth - tree.node(common).depth);
        const BspStats before = tree.stats();
        tree.reinsert(object, box);
        world.boxes[object] = box;
        ASSERT_EQ(tree.nodeOf(object), target);
        ASSERT_EQ(tree.stats().nodes_walked - before.nodes_walked, expected_walk)
            << "move " << move << " from node " << start << " to " << target;
        in_place += tree.stats().reinserts_in_place - before.reinserts_in_place;
        moved += tree.stats().reinserts_moved - before.reinserts_moved;
        ASSERT_EQ(tree.stats().reinserts_moved - before.reinserts_moved, start != target ? 1u : 0u);
        if (move % 50 == 0) tree.refitDirtyBounds();
    }
    EXPECT_GT(in_place, 300u);
    EXPECT_GT(moved, 300u);
    tree.refitDirtyBounds();
    expectTreeInvariants(tree);
}

TEST(BspTree, ReinsertMarksOldAndNewNodesAndTheirAncestorsDirtyEachOnce) {
    SmallWorld world(22);
    BspTree& tree = world.tree;
    const uint32_t object = world.deepLeafObject();
    ASSERT_NE(object, kNone);
    const uint32_t old_node = tree.nodeOf(object);
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) ASSERT_FALSE(tree.node(n).bounds_dirty);

    // Mirror the object to the opposite corner of the world: a different deep node.
    const Aabb& box = world.boxes[object];
    const Aabb mirrored = makeAabb(-box.max, -box.min);
    tree.reinsert(object, mirrored);
    const uint32_t new_node = tree.nodeOf(object);
    ASSERT_NE(new_node, old_node);

    std::set<uint32_t> expected_dirty;
    for (uint32_t n : ancestorsAndSelf(tree, old_node)) expected_dirty.insert(n);
    for (uint32_t n : ancestorsAndSelf(tree, new_node)) expected_dirty.insert(n);
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        EXPECT_EQ(tree.node(n).bounds_dirty, expected_dirty.count(n) == 1) << "node " << n;
    }

    // Reinserting again in place adds no new dirty nodes (each is listed once), so the refit
    // recomputes exactly the dirty set.
    tree.reinsert(object, mirrored);
    const uint64_t refit_before = tree.stats().nodes_refit;
    tree.refitDirtyBounds();
    EXPECT_EQ(tree.stats().nodes_refit - refit_before, expected_dirty.size());
    expectTreeInvariants(tree);

    // Nothing dirty: a refit does nothing.
    tree.refitDirtyBounds();
    EXPECT_EQ(tree.stats().nodes_refit - refit_before, expected_dirty.size());
}

TEST(BspTree, StatsCountReinsertsMovesWalkedNodesAndRefits) {
    SmallWorld world(23);
    BspTree& tree = world.tree;
    tree.resetStats();
    EXPECT_EQ(tree.stats().reinserts, 0u);
    EXPECT_EQ(tree.stats().nodes_refit, 0u);

    const uint32_t object = world.deepLeafObject();
    ASSERT_NE(object, kNone);
    const uint32_t depth = tree.node(tree.nodeOf(object)).depth;

    // Same box: counted, not moved, one node walked.
    tree.reinsert(object, world.boxes[object]);
    EXPECT_EQ(tree.stats().reinserts, 1u);
    EXPECT_EQ(tree.stats().reinserts_in_place, 1u);
    EXPECT_EQ(tree.stats().reinserts_moved, 0u);
    EXPECT_EQ(tree.stats().nodes_walked, 1u);

    // Far beyond any root growth: walks up to the root (depth + 1 nodes) and moves there.
    tree.reinsert(object, translated(world.boxes[object], glm::vec3(1e7f, 0.0f, 0.0f)));
    EXPECT_EQ(tree.stats().reinserts, 2u);
    EXPECT_EQ(tree.stats().reinserts_moved, 1u);
    EXPECT_EQ(tree.stats().root_growths, 0u);
    EXPECT_EQ(tree.nodeOf(object), tree.root());
    EXPECT_EQ(tree.stats().nodes_walked, 1u + depth + 1u);

    // Back again: walks down from the root to where it was (depth + 1 nodes).
    const uint64_t walked = tree.stats().nodes_walked;
    tree.reinsert(object, world.boxes[object]);
    EXPECT_EQ(tree.stats().reinserts_moved, 2u);
    EXPECT_EQ(tree.stats().nodes_walked - walked, depth + 1u);

    // Refit counts one per dirty node.
    uint32_t dirty = 0;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) dirty += tree.node(n).bounds_dirty ? 1 : 0;
    EXPECT_EQ(dirty, depth + 1u);
    tree.refitDirtyBounds();
    EXPECT_EQ(tree.stats().nodes_refit, dirty);
    expectTreeInvariants(tree);

    tree.resetStats();
    EXPECT_EQ(tree.stats().reinserts, 0u);
    EXPECT_EQ(tree.stats().reinserts_in_place, 0u);
    EXPECT_EQ(tree.stats().reinserts_moved, 0u);
    EXPECT_EQ(tree.stats().nodes_walked, 0u);
    EXPECT_EQ(tree.stats().nodes_refit, 0u);
}

TEST(BspTree, NonFiniteBoxMakesBoundsInfiniteUntilItBecomesFiniteAgain) {
    SmallWorld world(24);
    BspTree& tree = world.tree;
    const uint32_t object = world.deepLeafObject();
    ASSERT_NE(object, kNone);
    const uint32_t leaf = tree.nodeOf(object);

    Aabb broken = world.boxes[object];
    broken.max.z = kNan;
    tree.reinsert(object, broken);
    EXPECT_EQ(tree.nodeOf(object), tree.root());
    tree.refitDirtyBounds();
    EXPECT_TRUE(isInfiniteBox(tree.bounds(tree.root())));
    EXPECT_FALSE(isInfiniteBox(tree.bounds(leaf)));
    expectTreeInvariants(tree);

    tree.reinsert(object, world.boxes[object]);
    EXPECT_EQ(tree.nodeOf(object), leaf);
    tree.refitDirtyBounds();
    EXPECT_FALSE(isInfiniteBox(tree.bounds(tree.root())));
    expectTreeInvariants(tree);
}

}  // namespace
}  // namespace occsim
