// BspTree's build: the structural contract in bsp_tree.h checked from scratch (bsp_tree_checks.h)
// after a build; placement (loose cells, the centre's path, split planes, straddlers), the split
// rules, degenerate input, determinism and option validation. Moves and reinserts are in
// test_bsp_tree_moves.cpp, local adaptation in test_bsp_adaptation.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
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
using testing::objectsInInnerNodes;
using testing::placementByRule;
using testing::randomScene;
using testing::ruleName;
using testing::sameBox;
using testing::teapotField;
using testing::translated;

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
