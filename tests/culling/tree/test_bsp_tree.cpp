// BspTree: the structural contract in bsp_tree.h checked from scratch (bsp_tree_checks.h) after a
// build and after thousands of random moves; placement (loose cells, the centre's path, split
// planes, straddlers), the split rules, reinsert walks and their counters, dirty marking,
// degenerate input and option validation. Local adaptation is in test_bsp_adaptation.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "bsp_tree_checks.h"
#include "occsim/culling/tree/bsp_tree.h"

namespace occsim {
namespace {

using testing::ancestorsAndSelf;
using testing::describe;
using testing::expectTreeInvariants;
using testing::isInfiniteBox;
using testing::kInf;
using testing::kNan;
using testing::kNone;
using testing::objectsInInnerNodes;
using testing::placementByRule;
using testing::randomScene;
using testing::sameBox;
using testing::teapotField;
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

const char* ruleName(BspSplitRule rule) { return rule == BspSplitRule::Sah ? "Sah" : "Median"; }

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

TEST(BspTree, SahRuleCutsBetweenADenseAndASparseClusterWhereMedianCutsTheDenseOne) {
    // 1000 small boxes in x in [0, 1], 10 in x in [9, 10]. The median lies inside the dense
    // cluster; the surface area heuristic prefers a plane that wraps the dense cluster tightly.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Aabb> boxes;
    for (int i = 0; i < 1010; ++i) {
        const float x = (i < 1000 ? 0.0f : 9.0f) + 0.9f * unit(rng);
        const glm::vec3 low(x, 0.9f * unit(rng), 0.9f * unit(rng));
        boxes.push_back(makeAabb(low, low + glm::vec3(0.1f * unit(rng))));
    }
    BspBuildOptions options;
    options.split_rule = BspSplitRule::Sah;
    BspTree sah;
    sah.build(boxes, options);
    options.split_rule = BspSplitRule::Median;
    BspTree median;
    median.build(boxes, options);

    ASSERT_FALSE(sah.node(0).isLeaf());
    EXPECT_EQ(sah.node(0).axis, 0);
    // The plane hugs the dense cluster: at its edge or in the gap (trading a straddler or two for
    // a tighter child is a fair SAH bargain), never through its middle.
    EXPECT_GT(sah.node(0).split, 0.95f);
    EXPECT_LT(sah.node(0).split, 9.0f);
    EXPECT_LE(sah.node(0).object_count, 2u) << "almost no box straddles the chosen plane";

    ASSERT_FALSE(median.node(0).isLeaf());
    EXPECT_EQ(median.node(0).axis, 0);
    EXPECT_LT(median.node(0).split, 1.0f);

    expectTreeInvariants(sah);
    expectTreeInvariants(median);
}

TEST(BspTree, SahRuleChargesStraddlersToTheParentSoItAvoidsCuttingThroughManyObjects) {
    // 1000 thin rods spanning the scene in x, and 1000 small boxes spread through it. Any x plane
    // leaves every rod straddling in the root; a y or z plane cuts almost nothing. A heuristic
    // that forgot the straddlers' cost would find the x planes as cheap as the others.
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> coordinate(0.0f, 10.0f);
    std::vector<Aabb> boxes;
    for (int i = 0; i < 1000; ++i) {
        const float y = coordinate(rng);
        const float z = coordinate(rng);
        boxes.push_back(makeAabb({0.0f, y, z}, {10.0f, y + 0.05f, z + 0.05f}));
    }
    for (int i = 0; i < 1000; ++i) {
        const glm::vec3 low(coordinate(rng), coordinate(rng), coordinate(rng));
        boxes.push_back(makeAabb(low, low + glm::vec3(0.05f)));
    }
    BspBuildOptions options;
    options.split_rule = BspSplitRule::Sah;
    BspTree tree;
    tree.build(boxes, options);
    ASSERT_FALSE(tree.node(0).isLeaf());
    EXPECT_NE(tree.node(0).axis, 0);
    EXPECT_LT(tree.node(0).object_count, 50u);
    expectTreeInvariants(tree);
}

TEST(BspTree, RootCellIsTheSceneBoundsEnlargedByTheMarginOnEachSide) {
    const std::vector<Aabb> boxes = {
        makeAabb({-10.0f, 0.0f, 5.0f}, {-8.0f, 2.0f, 6.0f}),
        makeAabb({10.0f, 4.0f, -5.0f}, {12.0f, 6.0f, -4.0f}),
        makeAabb(glm::vec3(kNan), glm::vec3(kNan)),   // ignored by the root cell
        makeAabb(glm::vec3(-1e9f), glm::vec3(kInf)),  // so is this
    };
    BspBuildOptions options;
    options.root_margin = 0.25f;
    BspTree tree;
    tree.build(boxes, options);
    const Aabb& cell = tree.node(0).cell;
    // Scene bounds (-10, 0, -5) .. (12, 6, 6): extent (22, 6, 11).
    EXPECT_FLOAT_EQ(cell.min.x, -10.0f - 5.5f);
    EXPECT_FLOAT_EQ(cell.max.x, 12.0f + 5.5f);
    EXPECT_FLOAT_EQ(cell.min.y, 0.0f - 1.5f);
    EXPECT_FLOAT_EQ(cell.max.y, 6.0f + 1.5f);
    EXPECT_FLOAT_EQ(cell.min.z, -5.0f - 2.75f);
    EXPECT_FLOAT_EQ(cell.max.z, 6.0f + 2.75f);
    // The loose cell: the cell grown by the looseness times its extent on each side.
    const Aabb& loose = tree.node(0).loose_cell;
    const glm::vec3 size = extent(cell);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_FLOAT_EQ(loose.min[axis], cell.min[axis] - options.looseness * size[axis]);
        EXPECT_FLOAT_EQ(loose.max[axis], cell.max[axis] + options.looseness * size[axis]);
    }
    EXPECT_EQ(tree.builtRootCell().min, cell.min);
    EXPECT_EQ(tree.builtRootCell().max, cell.max);
    EXPECT_EQ(tree.nodeOf(2), tree.root());
    EXPECT_EQ(tree.nodeOf(3), tree.root());
    EXPECT_TRUE(isInfiniteBox(tree.bounds(0)));
    expectTreeInvariants(tree);
}

TEST(BspTree, CellsNeverDegenerateForFlatScenesOrScenesWithoutFiniteBoxes) {
    // Every box in the plane y = 3, and all points on one line along x.
    std::vector<Aabb> flat;
    for (int i = 0; i < 200; ++i) {
        const float x = static_cast<float>(i);
        flat.push_back(makeAabb({x, 3.0f, 0.0f}, {x, 3.0f, 0.0f}));
    }
    BspBuildOptions options;
    options.root_margin = 0.0f;
    BspTree tree;
    tree.build(flat, options);
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const glm::vec3 size = extent(tree.node(n).cell);
        EXPECT_GT(size.x, 0.0f) << "node " << n;
        EXPECT_GT(size.y, 0.0f) << "node " << n;
        EXPECT_GT(size.z, 0.0f) << "node " << n;
    }
    EXPECT_GT(tree.nodeCount(), 1u);
    expectTreeInvariants(tree);

    // No finite box at all: a unit cube at the origin (plus margin), one leaf holding everything.
    const std::vector<Aabb> none = {Aabb{}, makeAabb(glm::vec3(kNan), glm::vec3(1.0f))};
    BspTree empty_tree;
    empty_tree.build(none, BspBuildOptions{});
    const Aabb& cell = empty_tree.node(0).cell;
    EXPECT_TRUE(contains(cell, makeAabb(glm::vec3(-0.5f), glm::vec3(0.5f))));
    EXPECT_LT(glm::length(extent(cell)), 3.0f);
    EXPECT_EQ(empty_tree.nodeCount(), 1u);
    EXPECT_EQ(empty_tree.node(0).object_count, 2u);
    expectTreeInvariants(empty_tree);

    BspTree no_objects;
    no_objects.build({}, BspBuildOptions{});
    EXPECT_EQ(no_objects.nodeCount(), 1u);
    EXPECT_TRUE(isEmpty(no_objects.bounds(0)));
    expectTreeInvariants(no_objects);
}

TEST(BspTree, BuildStopsAtMaxDepthAndAtMaxObjectsPerLeaf) {
    std::mt19937 rng(3);
    const std::vector<Aabb> boxes = randomScene(rng, 3000, glm::vec3(50.0f));
    for (BspSplitRule rule : {BspSplitRule::Median, BspSplitRule::Sah}) {
        BspBuildOptions options;
        options.split_rule = rule;
        options.max_depth = 3;
        options.max_objects_per_leaf = 1;
        BspTree shallow;
        shallow.build(boxes, options);
        EXPECT_EQ(shallow.maxDepth(), 3u) << ruleName(rule);
        EXPECT_LE(shallow.nodeCount(), 15u) << ruleName(rule);

        options.max_depth = 0;
        BspTree root_only;
        root_only.build(boxes, options);
        EXPECT_EQ(root_only.nodeCount(), 1u) << ruleName(rule);
        EXPECT_EQ(root_only.maxDepth(), 0u) << ruleName(rule);

        options.max_depth = 64;
        options.max_objects_per_leaf = 3000;
        BspTree one_leaf;
        one_leaf.build(boxes, options);
        EXPECT_EQ(one_leaf.nodeCount(), 1u) << ruleName(rule);

        // A subtree is split only while it holds more than max_objects_per_leaf objects.
        options.max_objects_per_leaf = 8;
        BspTree tree;
        tree.build(boxes, options);
        std::vector<uint32_t> subtree_objects(tree.nodeCount(), 0);
        for (uint32_t n = tree.nodeCount(); n-- > 0;) {
            subtree_objects[n] += tree.node(n).object_count;
            if (n != 0) subtree_objects[tree.node(n).parent] += subtree_objects[n];
        }
        for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
            if (!tree.node(n).isLeaf()) {
                EXPECT_GT(subtree_objects[n], 8u) << ruleName(rule) << " node " << n;
            }
        }
        expectTreeInvariants(tree);
    }
}

TEST(BspTree, IdenticalObjectsDoNotCauseUselessSplits) {
    // Splitting can never separate identical boxes, so the tree must stay a single leaf instead
    // of running down to max_depth.
    for (BspSplitRule rule : {BspSplitRule::Median, BspSplitRule::Sah}) {
        for (const Aabb& box : {makeAabb(glm::vec3(1.0f), glm::vec3(1.0f)),
                                makeAabb(glm::vec3(1.0f), glm::vec3(2.0f))}) {
            const std::vector<Aabb> boxes(100, box);
            BspBuildOptions options;
            options.split_rule = rule;
            options.max_depth = 64;
            BspTree tree;
            tree.build(boxes, options);
            EXPECT_EQ(tree.nodeCount(), 1u) << ruleName(rule);
            expectTreeInvariants(tree);
        }
    }
}

TEST(BspTree, StraddlersOfSplitPlanesReachLeavesWithLooseCellsAndStayInInnerNodesWithout) {
    // The default scenario's field: with plain cells (looseness 0) a large share of the objects
    // straddle some split and stay in inner nodes; with loose cells they reach leaves.
    const std::vector<Aabb> boxes = teapotField(3000, 1);
    for (BspSplitRule rule : {BspSplitRule::Median, BspSplitRule::Sah}) {
        BspBuildOptions options;
        options.split_rule = rule;
        options.looseness = 0.0f;
        BspTree plain;
        plain.build(boxes, options);
        EXPECT_GT(objectsInInnerNodes(plain), 900u) << ruleName(rule);
        expectTreeInvariants(plain);

        options.looseness = 0.5f;
        BspTree loose;
        loose.build(boxes, options);
        EXPECT_LT(objectsInInnerNodes(loose), 30u) << ruleName(rule);  // under 1%
        EXPECT_EQ(loose.node(loose.root()).object_count, 0u) << ruleName(rule);
        expectTreeInvariants(loose);
    }
}

TEST(BspTree, LooseCellsNestAndSiblingsShareTheirMarginAtThePlane) {
    std::mt19937 rng(8);
    const std::vector<Aabb> boxes = randomScene(rng, 1500, glm::vec3(60.0f, 20.0f, 40.0f));
    for (float looseness : {0.0f, 0.25f, 0.5f, 1.0f, 4.0f}) {
        BspBuildOptions options;
        options.split_rule = BspSplitRule::Sah;
        options.looseness = looseness;
        BspTree tree;
        tree.build(boxes, options);
        expectTreeInvariants(tree);  // nesting and the shared margin are part of the contract
        for (uint32_t n = 1; n < tree.nodeCount(); ++n) {
            const BspNode& node = tree.node(n);
            const BspNode& parent = tree.node(node.parent);
            const int axis = parent.axis;
            // Along the split axis: the looseness times the larger sibling's extent, at most the
            // parent's margin (and clamped into the parent's loose cell).
            const float larger = std::max(parent.split - parent.cell.min[axis],
                                          parent.cell.max[axis] - parent.split);
            const float margin = node.loose_cell.max[axis] - node.cell.max[axis];
            if (node.loose_cell.max[axis] < parent.loose_cell.max[axis]) {
                EXPECT_LE(margin, looseness * larger * 1.0001f + 1e-6f) << "node " << n;
            }
            if (looseness == 0.0f) {
                EXPECT_TRUE(sameBox(node.loose_cell, node.cell)) << "node " << n;
            }
        }
    }
}

TEST(BspTree, ObjectsOnSplitPlanesFollowTheirCentre) {
    // Four point-sized clusters around a median plane at x = 0; boxes on the plane itself, or
    // touching it from either side, go where their centre says.
    std::vector<Aabb> boxes;
    for (int i = 0; i < 40; ++i) {
        const float x = (i % 2 == 0 ? -10.0f : 10.0f) + 0.01f * static_cast<float>(i);
        const float z = static_cast<float>(i % 5);
        boxes.push_back(makeAabb({x, 0.0f, z}, {x + 0.5f, 0.5f, z + 0.5f}));
    }
    BspBuildOptions options;
    options.max_objects_per_leaf = 8;
    BspTree tree;
    tree.build(boxes, options);
    const BspNode& root = tree.node(tree.root());
    ASSERT_FALSE(root.isLeaf());
    ASSERT_EQ(root.axis, 0);
    const float s = root.split;
    const auto under = [&](uint32_t object, uint32_t child) {
        const std::vector<uint32_t> path = ancestorsAndSelf(tree, tree.nodeOf(object));
        return std::find(path.begin(), path.end(), child) != path.end();
    };
    const uint32_t o = 0;
    // Zero thickness on the plane: the centre is on the plane, which counts as below.
    tree.reinsert(o, makeAabb({s, 0.0f, 0.0f}, {s, 0.5f, 0.5f}));
    EXPECT_TRUE(under(o, root.child[0]));
    // Touching from above: the centre is above.
    tree.reinsert(o, makeAabb({s, 0.0f, 0.0f}, {s + 0.5f, 0.5f, 0.5f}));
    EXPECT_TRUE(under(o, root.child[1]));
    // Touching from below.
    tree.reinsert(o, makeAabb({s - 0.5f, 0.0f, 0.0f}, {s, 0.5f, 0.5f}));
    EXPECT_TRUE(under(o, root.child[0]));
    // Straddling, centre a little above: still reaches the child above (loose cells).
    tree.reinsert(o, makeAabb({s - 0.2f, 0.0f, 0.0f}, {s + 0.3f, 0.5f, 0.5f}));
    EXPECT_TRUE(under(o, root.child[1]));
    tree.refitDirtyBounds();
    expectTreeInvariants(tree);  // every object where placementByRule() puts it
}

TEST(BspTree, DegenerateInputBuildsAndReinsertsKeepingEveryInvariant) {
    BspBuildOptions options;
    options.max_objects_per_leaf = 2;

    // No objects: one empty leaf; a refit does nothing.
    BspTree none;
    none.build({}, options);
    EXPECT_EQ(none.nodeCount(), 1u);
    EXPECT_TRUE(isEmpty(none.bounds(0)));
    none.refitDirtyBounds();
    expectTreeInvariants(none);

    // One object: a single leaf holding it, which it keeps through moves.
    const std::vector<Aabb> one = {makeAabb({1, 2, 3}, {2, 3, 4})};
    BspTree single;
    single.build(one, options);
    EXPECT_EQ(single.nodeCount(), 1u);
    EXPECT_EQ(single.nodeOf(0), 0u);
    single.reinsert(0, makeAabb({1.5f, 2, 3}, {2.5f, 3, 4}));
    single.refitDirtyBounds();
    expectTreeInvariants(single);

    // Zero-extent boxes (points), many of them on the same coordinates along some axes.
    std::vector<Aabb> points;
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 p(static_cast<float>(i % 10), static_cast<float>(i % 3),
                          static_cast<float>(i / 10));
        points.push_back(makeAabb(p, p));
    }
    BspTree point_tree;
    point_tree.build(points, options);
    EXPECT_GT(point_tree.nodeCount(), 50u);
    EXPECT_EQ(objectsInInnerNodes(point_tree), 0u) << "a point fits every cell containing it";
    for (uint32_t o = 0; o < 300; o += 7) {
        const glm::vec3 p = points[(o * 31) % 300].min;
        point_tree.reinsert(o, makeAabb(p, p));
    }
    point_tree.refitDirtyBounds();
    expectTreeInvariants(point_tree);

    // All objects at one point: nothing separates them, so one leaf, at any leaf size; moves
    // and a refit change nothing structural.
    const std::vector<Aabb> pile(50, makeAabb(glm::vec3(5.0f), glm::vec3(5.0f)));
    BspTree pile_tree;
    pile_tree.build(pile, options);
    EXPECT_EQ(pile_tree.nodeCount(), 1u);
    const uint64_t version = pile_tree.structureVersion();
    for (uint32_t o = 0; o < 50; ++o) pile_tree.reinsert(o, pile[o]);
    pile_tree.refitDirtyBounds();
    EXPECT_EQ(pile_tree.structureVersion(), version);
    expectTreeInvariants(pile_tree);

    // A NaN box lives in the root with infinite bounds, so no culler skips it; the nodes not above
    // it keep finite bounds.
    std::mt19937 rng(9);
    std::vector<Aabb> boxes = randomScene(rng, 200, glm::vec3(20.0f));
    boxes[17] = makeAabb(glm::vec3(kNan), glm::vec3(kNan));
    BspTree with_nan;
    with_nan.build(boxes, options);
    EXPECT_EQ(with_nan.nodeOf(17), with_nan.root());
    EXPECT_TRUE(isInfiniteBox(with_nan.bounds(with_nan.root())));
    for (uint32_t n = 1; n < with_nan.nodeCount(); ++n) {
        EXPECT_FALSE(isInfiniteBox(with_nan.bounds(n))) << "node " << n;
    }
    expectTreeInvariants(with_nan);
}

TEST(BspTree, SameInputGivesTheSameTreeAndTheSameDecisions) {
    std::mt19937 rng(31);
    std::vector<Aabb> boxes = randomScene(rng, 1500, glm::vec3(50.0f));
    BspBuildOptions options;
    options.split_rule = BspSplitRule::Sah;
    BspTree a, b;
    a.build(boxes, options);
    b.build(boxes, options);
    std::normal_distribution<float> step(0.0f, 3.0f);
    for (int frame = 0; frame < 50; ++frame) {
        for (uint32_t o = 0; o < 300; ++o) {
            boxes[o] = translated(boxes[o], glm::vec3(step(rng), step(rng), step(rng)));
            a.reinsert(o, boxes[o]);
            b.reinsert(o, boxes[o]);
        }
        a.refitDirtyBounds();
        b.refitDirtyBounds();
    }
    ASSERT_EQ(a.nodeCount(), b.nodeCount());
    EXPECT_EQ(a.structureVersion(), b.structureVersion());
    for (uint32_t n = 0; n < a.nodeCount(); ++n) {
        const BspNode& x = a.node(n);
        const BspNode& y = b.node(n);
        EXPECT_TRUE(sameBox(x.cell, y.cell) && sameBox(x.bounds, y.bounds) &&
                    x.child[0] == y.child[0] && x.child[1] == y.child[1] &&
                    x.first_object == y.first_object && x.live == y.live)
            << "node " << n;
    }
    for (uint32_t o = 0; o < a.objectCount(); ++o) {
        EXPECT_EQ(a.nodeOf(o), b.nodeOf(o));
        EXPECT_EQ(a.nextObject(o), b.nextObject(o));
    }
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

TEST(BspTree, OptionValidationRejectsOutOfRangeValuesAndNamesTheOption) {
    EXPECT_TRUE(BspBuildOptions{}.isValid(nullptr));
    std::string error;
    EXPECT_TRUE(BspBuildOptions{}.isValid(&error));

    struct Case {
        BspBuildOptions options;
        const char* option_name;
    };
    std::vector<Case> cases;
    auto add = [&cases](const char* option_name, auto change) {
        BspBuildOptions o;
        change(o);
        cases.push_back({o, option_name});
    };
    add("max_depth", [](BspBuildOptions& o) { o.max_depth = 65; });
    add("max_depth", [](BspBuildOptions& o) { o.max_depth = UINT32_MAX; });
    add("max_objects_per_leaf", [](BspBuildOptions& o) { o.max_objects_per_leaf = 0; });
    add("root_margin", [](BspBuildOptions& o) { o.root_margin = -0.01f; });
    add("root_margin", [](BspBuildOptions& o) { o.root_margin = 10.5f; });
    add("root_margin", [](BspBuildOptions& o) { o.root_margin = kNan; });
    add("root_margin", [](BspBuildOptions& o) { o.root_margin = kInf; });
    add("looseness", [](BspBuildOptions& o) { o.looseness = -0.1f; });
    add("looseness", [](BspBuildOptions& o) { o.looseness = 4.5f; });
    add("looseness", [](BspBuildOptions& o) { o.looseness = kNan; });
    add("max_root_growth", [](BspBuildOptions& o) { o.max_root_growth = 0.5f; });
    add("max_root_growth", [](BspBuildOptions& o) { o.max_root_growth = kInf; });
    for (const Case& c : cases) {
        error.clear();
        EXPECT_FALSE(c.options.isValid(&error)) << c.option_name;
        EXPECT_NE(error.find(c.option_name), std::string::npos) << "message: " << error;
        EXPECT_FALSE(c.options.isValid(nullptr)) << c.option_name;
    }
    // Range ends are valid.
    BspBuildOptions edges;
    edges.max_depth = 64;
    edges.max_objects_per_leaf = 1;
    edges.root_margin = 10.0f;
    edges.looseness = 4.0f;
    edges.max_root_growth = 1e6f;
    EXPECT_TRUE(edges.isValid(nullptr));
    edges.max_depth = 0;
    edges.root_margin = 0.0f;
    edges.looseness = 0.0f;
    edges.max_root_growth = 1.0f;
    EXPECT_TRUE(edges.isValid(nullptr));
}

}  // namespace
}  // namespace occsim
