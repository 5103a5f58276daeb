// BspTree local adaptation (occsim/culling/tree/bsp_tree.h): crowded leaves split, emptied leaves
// merge, the root cell grows for movers that leave it; all without a rebuild, keeping every
// invariant (bsp_tree_checks.h) and the per-node state contract (BspNode::generation,
// structureVersion(), NodeStateArray).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "bsp_tree_checks.h"
#include "occsim/culling/tree/bsp_tree.h"
#include "occsim/culling/tree/node_state.h"

namespace occsim {
namespace {

using testing::ancestorsAndSelf;
using testing::expectTreeInvariants;
using testing::kNone;
using testing::objectsInInnerNodes;
using testing::placementByRule;
using testing::randomScene;
using testing::sameBox;
using testing::teapotField;
using testing::translated;

// What refitDirtyBounds() merges never remains after it: an inner node with two leaf children
// holding at most half a leaf's worth of objects, or one empty child and at most a leaf's worth.
void expectNothingLeftToMerge(const BspTree& tree) {
    const uint32_t max_leaf = tree.options().max_objects_per_leaf;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const BspNode& node = tree.node(n);
        if (!node.live || node.isLeaf()) continue;
        const BspNode& below = tree.node(node.child[0]);
        const BspNode& above = tree.node(node.child[1]);
        if (!below.isLeaf() || !above.isLeaf()) continue;
        const bool one_empty = below.object_count == 0 || above.object_count == 0;
        EXPECT_FALSE(node.subtree_object_count <= max_leaf / 2 ||
                     (one_empty && node.subtree_object_count <= max_leaf))
            << "node " << n << " holds " << node.subtree_object_count << " objects";
    }
}

// Every leaf holds at most max_objects_per_leaf objects unless they cannot be separated.
void expectLeavesWithinTheLimit(const BspTree& tree) {
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const BspNode& node = tree.node(n);
        if (!node.live || !node.isLeaf()) continue;
        EXPECT_LE(node.object_count, tree.options().max_objects_per_leaf) << "leaf " << n;
    }
}

std::map<uint32_t, uint32_t> generations(const BspTree& tree) {
    std::map<uint32_t, uint32_t> out;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        if (tree.isLive(n)) out[n] = tree.node(n).generation;
    }
    return out;
}

bool isDescendantOrSelf(const BspTree& tree, uint32_t node, uint32_t ancestor) {
    const std::vector<uint32_t> path = ancestorsAndSelf(tree, node);
    return std::find(path.begin(), path.end(), ancestor) != path.end();
}

// A leaf at depth >= 4 holding objects, and the objects of the tree that lie far from it.
struct Field {
    std::vector<Aabb> boxes;
    BspTree tree;

    explicit Field(uint32_t count = 800, uint32_t seed = 3) {
        boxes = teapotField(count, seed);
        BspBuildOptions options;
        options.split_rule = BspSplitRule::Sah;
        tree.build(boxes, options);
    }

    uint32_t deepLeaf() const {
        for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
            const BspNode& node = tree.node(n);
            if (node.live && node.isLeaf() && node.depth >= 4 && node.object_count > 0) return n;
        }
        return kNone;
    }

    void move(uint32_t object, const Aabb& box) {
        boxes[object] = box;
        tree.reinsert(object, box);
    }
};

TEST(BspAdaptation, CrowdedLeafIsSplitByRebuildingOnlyTheSmallSubtreeAroundIt) {
    Field field;
    BspTree& tree = field.tree;
    const uint32_t leaf = field.deepLeaf();
    ASSERT_NE(leaf, kNone);
    const Aabb cell = tree.node(leaf).cell;
    const auto before = generations(tree);
    const uint64_t version = tree.structureVersion();

    // Twelve objects from the far end of the field, shrunk into distinct spots of the leaf's cell.
    std::vector<uint32_t> movers;
    for (uint32_t o = 0; o < tree.objectCount() && movers.size() < 12; ++o) {
        const glm::vec3 c = center(field.boxes[o]);
        if (glm::distance(c, center(cell)) > 60.0f) movers.push_back(o);
    }
    ASSERT_EQ(movers.size(), 12u);
    for (size_t k = 0; k < movers.size(); ++k) {
        const glm::vec3 f(0.1f + 0.8f * static_cast<float>(k % 3) / 2.0f,
                          0.1f + 0.8f * static_cast<float>((k / 3) % 2),
                          0.1f + 0.8f * static_cast<float>(k / 6));
        const glm::vec3 p = glm::mix(cell.min, cell.max, f);
        const glm::vec3 half = 0.02f * extent(cell);
        field.move(movers[k], makeAabb(p - half, p + half));
    }
    ASSERT_GT(tree.node(leaf).object_count, tree.options().max_objects_per_leaf);
    tree.refitDirtyBounds();

    EXPECT_GE(tree.stats().splits, 1u);
    EXPECT_GT(tree.structureVersion(), version);
    expectTreeInvariants(tree);
    expectLeavesWithinTheLimit(tree);
    expectNothingLeftToMerge(tree);

    // Local: the nodes holding new generations all lie under one ancestor of the crowded leaf,
    // whose subtree is small; every other node kept its generation.
    const auto after = generations(tree);
    std::vector<uint32_t> fresh;
    for (const auto& [n, generation] : after) {
        auto old = before.find(n);
        if (old == before.end() || old->second != generation) fresh.push_back(n);
    }
    ASSERT_FALSE(fresh.empty());
    uint32_t top = kNone;
    for (uint32_t a : ancestorsAndSelf(tree, fresh.front())) {
        bool covers_all = true;
        for (uint32_t n : fresh) covers_all &= isDescendantOrSelf(tree, n, a) && n != a;
        if (covers_all) {
            top = a;
            break;
        }
    }
    ASSERT_NE(top, kNone);
    EXPECT_EQ(before.at(top), after.at(top)) << "the top of the rebuilt subtree keeps its state";
    EXPECT_LE(tree.node(top).subtree_object_count, 2 * 4u + 12u);
    EXPECT_LE(fresh.size(), 2u * tree.node(top).subtree_object_count);
}

TEST(BspAdaptation, EmptiedLeavesMergeAndTheirSlotsAreReusedWhenMoversReturn) {
    Field field;
    BspTree& tree = field.tree;
    const uint32_t built_live = tree.liveNodeCount();
    const uint32_t built_slots = tree.nodeCount();

    // Everything in the far half of the field leaves for good (beyond any root growth).
    std::vector<uint32_t> gone;
    for (uint32_t o = 0; o < tree.objectCount(); ++o) {
        if (center(field.boxes[o]).z < -100.0f) gone.push_back(o);
    }
    ASSERT_GT(gone.size(), 300u);
    std::vector<Aabb> home(field.boxes);
    for (uint32_t o : gone) field.move(o, translated(field.boxes[o], glm::vec3(0, 0, -1e8f)));
    const uint64_t version = tree.structureVersion();
    tree.refitDirtyBounds();

    EXPECT_GT(tree.stats().merges, 50u);
    EXPECT_GT(tree.structureVersion(), version);
    EXPECT_LT(tree.liveNodeCount(), built_live * 2 / 3);
    EXPECT_EQ(tree.stats().root_growths, 0u);
    expectTreeInvariants(tree);
    expectNothingLeftToMerge(tree);

    // They come back: crowded leaves split again, reusing freed slots (children still after
    // their parents), and the array ends no larger than it was.
    for (uint32_t o : gone) field.move(o, home[o]);
    tree.refitDirtyBounds();
    EXPECT_GT(tree.stats().splits, 0u);
    expectTreeInvariants(tree);
    expectLeavesWithinTheLimit(tree);
    EXPECT_LE(tree.nodeCount(), built_slots + built_slots / 4);
    EXPECT_EQ(objectsInInnerNodes(tree), 0u);
}

TEST(BspAdaptation, MoversLeavingTheRootCellGrowItAndTheBoundaryCellsAndReachLeavesThere) {
    Field field;
    BspTree& tree = field.tree;
    const Aabb built = tree.node(tree.root()).cell;
    const float width = built.max.x - built.min.x;
    const auto before = generations(tree);
    const uint64_t version = tree.structureVersion();

    // A mover 30% of the field's width beyond its +x face.
    const uint32_t object = 5;
    const Aabb home = field.boxes[object];
    const Aabb outside = translated(home, glm::vec3(built.max.x + 0.3f * width - home.min.x, 0, 0));
    field.move(object, outside);
    EXPECT_EQ(tree.stats().root_growths, 1u);
    EXPECT_TRUE(contains(tree.node(tree.root()).cell, outside));
    EXPECT_NE(tree.nodeOf(object), tree.root());
    EXPECT_TRUE(tree.node(tree.nodeOf(object)).isLeaf());
    EXPECT_EQ(tree.nodeOf(object), placementByRule(tree, outside));
    // Growth changes cells only: no new node, no new structure version, the build's cell kept.
    EXPECT_EQ(tree.structureVersion(), version);
    EXPECT_EQ(generations(tree), before);
    EXPECT_TRUE(sameBox(tree.builtRootCell(), built));
    // The boundary cells moved with the root's face; every other face stayed.
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        EXPECT_LE(tree.node(n).cell.max.x, tree.node(tree.root()).cell.max.x) << n;
    }
    tree.refitDirtyBounds();
    expectTreeInvariants(tree);

    // A little further: still inside the grown cell (the growth left slack), no new growth.
    field.move(object, translated(outside, glm::vec3(0.05f * width, 0, 0)));
    EXPECT_EQ(tree.stats().root_growths, 1u);

    // Back home: where the rule puts it, and the root cell stays grown.
    field.move(object, home);
    EXPECT_EQ(tree.nodeOf(object), placementByRule(tree, home));
    EXPECT_GT(tree.node(tree.root()).cell.max.x, built.max.x);
    tree.refitDirtyBounds();
    expectTreeInvariants(tree);
}

TEST(BspAdaptation, MoversBeyondTheGrowthCapLiveInTheRootUntilTheyReturn) {
    Field field;
    BspTree& tree = field.tree;
    const Aabb built = tree.node(tree.root()).cell;
    const glm::vec3 size = extent(built);
    const float largest = std::max(size.x, std::max(size.y, size.z));
    const uint32_t object = 7;
    const Aabb home = field.boxes[object];

    // Beyond max_root_growth times the largest extent: no growth, the root holds it, its bounds
    // (finite) include it.
    const Aabb lost =
        translated(home, glm::vec3(0, 2.0f * tree.options().max_root_growth * largest, 0));
    field.move(object, lost);
    EXPECT_EQ(tree.stats().root_growths, 0u);
    EXPECT_TRUE(sameBox(tree.node(tree.root()).cell, built));
    EXPECT_EQ(tree.nodeOf(object), tree.root());
    tree.refitDirtyBounds();
    EXPECT_TRUE(contains(tree.bounds(tree.root()), lost));
    expectTreeInvariants(tree);

    field.move(object, home);
    EXPECT_EQ(tree.nodeOf(object), placementByRule(tree, home));
    EXPECT_NE(tree.nodeOf(object), tree.root());
    tree.refitDirtyBounds();
    expectTreeInvariants(tree);
}

TEST(BspAdaptation, MoversFasterThanACellPerFrameAreReplacedExactly) {
    // 200 of 1500 objects jump tens of cells every frame, to anywhere in the field and at times
    // a little outside it; the rest stand still.
    Field field(1500, 4);
    BspTree& tree = field.tree;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> jump(-60.0f, 60.0f);
    for (int frame = 1; frame <= 200; ++frame) {
        const BspStats before = tree.stats();
        for (uint32_t o = 0; o < 200; ++o) {
            Aabb box = translated(field.boxes[o],
                                  glm::vec3(jump(rng), 0.5f * jump(rng) / 60.0f, 2.0f * jump(rng)));
            // Keep them roughly in the field (bouncing off a wide margin around it).
            const glm::vec3 c = center(box);
            if (std::abs(c.x) > 45.0f) box = translated(box, glm::vec3(-c.x, 0, 0));
            if (c.z < -215.0f || c.z > 15.0f) box = translated(box, glm::vec3(0, 0, -100.0f - c.z));
            field.move(o, box);
            ASSERT_EQ(tree.nodeOf(o), placementByRule(tree, box)) << "frame " << frame;
        }
        // A walk never visits more than the way up to the root and down again (plus, at a
        // growth, the objects growth re-placed).
        const BspStats& after = tree.stats();
        const uint64_t walked = after.nodes_walked - before.nodes_walked;
        if (after.root_growths == before.root_growths) {
            EXPECT_LE(walked, 200u * (2u * tree.maxDepth() + 1u)) << "frame " << frame;
        }
        tree.refitDirtyBounds();
        if (frame % 40 == 0) {
            expectTreeInvariants(tree);
            if (HasFatalFailure()) return;
        }
    }
    EXPECT_GT(tree.stats().reinserts_moved, 200u * 200u * 9 / 10) << "they did cross cells";
    expectLeavesWithinTheLimit(tree);
    expectNothingLeftToMerge(tree);
}

TEST(BspAdaptation, StructureVersionAndGenerationsChangeExactlyForNewNodes) {
    Field field;
    BspTree& tree = field.tree;

    // Small moves, no structural change: nothing changes.
    auto before = generations(tree);
    uint64_t version = tree.structureVersion();
    for (uint32_t o = 0; o < 50; ++o) {
        const Aabb& b = field.boxes[o];
        const glm::vec3 c = center(b);
        field.move(o, makeAabb(glm::mix(b.min, c, 0.1f), glm::mix(b.max, c, 0.1f)));
    }
    tree.refitDirtyBounds();
    ASSERT_EQ(tree.stats().splits + tree.stats().merges, 0u);
    EXPECT_EQ(tree.structureVersion(), version);
    EXPECT_EQ(generations(tree), before);

    // A merge: an emptied pair of leaves; the parent keeps its generation, the children's
    // slots are freed.
    uint32_t pair = kNone;
    for (uint32_t n = 0; n < tree.nodeCount() && pair == kNone; ++n) {
        const BspNode& node = tree.node(n);
        if (node.live && !node.isLeaf() && tree.node(node.child[0]).isLeaf() &&
            tree.node(node.child[1]).isLeaf()) {
            pair = n;
        }
    }
    ASSERT_NE(pair, kNone);
    const uint32_t children[2] = {tree.node(pair).child[0], tree.node(pair).child[1]};
    std::vector<uint32_t> leaving;
    for (uint32_t c : children) {
        for (uint32_t o = tree.firstObject(c); o != kNone; o = tree.nextObject(o))
            leaving.push_back(o);
    }
    for (uint32_t o : leaving) field.move(o, translated(field.boxes[o], glm::vec3(1e8f, 0, 0)));
    before = generations(tree);
    version = tree.structureVersion();
    tree.refitDirtyBounds();
    EXPECT_GT(tree.structureVersion(), version);
    EXPECT_TRUE(tree.node(pair).isLeaf());
    EXPECT_EQ(tree.node(pair).generation, before.at(pair));
    for (uint32_t c : children) EXPECT_TRUE(c >= tree.nodeCount() || !tree.isLive(c)) << c;
    for (const auto& [n, generation] : generations(tree)) {
        EXPECT_EQ(before.at(n), generation) << "a merge creates no node, node " << n;
    }

    // They return: the pair's node splits again; its slot keeps its generation, the new nodes
    // have generations never used before.
    // Generations come from a counter: a new node's exceeds every one handed out before.
    uint32_t highest = 0;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n)
        highest = std::max(highest, tree.node(n).generation);
    for (const auto& [n, generation] : before) highest = std::max(highest, generation);
    before = generations(tree);
    version = tree.structureVersion();
    for (uint32_t o : leaving) field.move(o, translated(field.boxes[o], glm::vec3(-1e8f, 0, 0)));
    tree.refitDirtyBounds();
    if (tree.node(pair).object_count + leaving.size() > tree.options().max_objects_per_leaf) {
        EXPECT_GT(tree.structureVersion(), version);
    }
    // The new nodes form one rebuilt subtree: below one surviving node, which kept its state.
    const auto after = generations(tree);
    auto is_new = [&](uint32_t n) {
        auto old = before.find(n);
        return old == before.end() || old->second != after.at(n);
    };
    std::set<uint32_t> tops;
    for (const auto& [n, generation] : after) {
        if (!is_new(n)) continue;
        EXPECT_GT(generation, highest) << "node " << n << " is new";
        uint32_t up = tree.node(n).parent;
        while (up != kNone && is_new(up)) up = tree.node(up).parent;
        ASSERT_NE(up, kNone) << "the root is never new";
        tops.insert(up);
    }
    EXPECT_LE(tops.size(), 1u);
    expectTreeInvariants(tree);
}

TEST(BspAdaptation, NodeStateArrayKeepsTheStateOfUnchangedNodesAcrossSplitsAndMerges) {
    Field field;
    BspTree& tree = field.tree;
    NodeStateArray<int> state;
    state.reset(tree);
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) state[n] = static_cast<int>(n) + 1000;
    const auto before = generations(tree);

    // A merge in one place, a split in another, in the same frame.
    std::vector<uint32_t> far;
    for (uint32_t o = 0; o < tree.objectCount(); ++o) {
        if (center(field.boxes[o]).z < -150.0f) far.push_back(o);
    }
    const uint32_t leaf = field.deepLeaf();
    const Aabb cell = tree.node(leaf).cell;
    for (size_t k = 0; k < far.size(); ++k) {
        if (k < 10) {
            const glm::vec3 p =
                glm::mix(cell.min, cell.max, glm::vec3(0.05f + 0.09f * k, 0.5f, 0.5f));
            field.move(far[k], makeAabb(p - 0.01f, p + 0.01f));
        } else {
            field.move(far[k], translated(field.boxes[far[k]], glm::vec3(0, 0, -1e8f)));
        }
    }
    tree.refitDirtyBounds();
    ASSERT_GT(tree.stats().merges, 0u);
    ASSERT_GT(tree.stats().splits, 0u);

    state.sync(tree);
    ASSERT_EQ(state.size(), tree.nodeCount());
    uint32_t kept = 0, reset = 0;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        if (!tree.isLive(n)) continue;
        auto old = before.find(n);
        if (old != before.end() && old->second == tree.node(n).generation) {
            EXPECT_EQ(state[n], static_cast<int>(n) + 1000) << "unchanged node " << n;
            ++kept;
        } else {
            EXPECT_EQ(state[n], 0) << "new node " << n;
            ++reset;
        }
    }
    EXPECT_GT(kept, 100u);
    EXPECT_GT(reset, 0u);
    // Nothing changed since: sync keeps everything.
    state[0] = 7;
    state.sync(tree);
    EXPECT_EQ(state[0], 7);
}

TEST(BspAdaptation, WithAdaptationOffTheBuiltCellsNeverChange) {
    std::mt19937 rng(12);
    std::vector<Aabb> boxes = randomScene(rng, 1000, glm::vec3(50.0f));
    BspBuildOptions options;
    options.adapt = false;
    BspTree tree;
    tree.build(boxes, options);
    std::vector<Aabb> cells;
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) cells.push_back(tree.node(n).cell);
    const uint64_t version = tree.structureVersion();

    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (int move = 0; move < 3000; ++move) {
        const uint32_t o = rng() % 1000;
        // Into one corner (crowding), out of the root cell, or anywhere.
        const glm::vec3 to = move % 3 == 0   ? glm::vec3(40.0f) + unit(rng)
                             : move % 3 == 1 ? glm::vec3(200.0f * unit(rng), 300.0f, 0.0f)
                                             : 50.0f * glm::vec3(unit(rng), unit(rng), unit(rng));
        boxes[o] = translated(boxes[o], to - center(boxes[o]));
        tree.reinsert(o, boxes[o]);
        if (move % 100 == 0) tree.refitDirtyBounds();
    }
    tree.refitDirtyBounds();
    EXPECT_EQ(tree.structureVersion(), version);
    ASSERT_EQ(tree.nodeCount(), cells.size());
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        EXPECT_TRUE(sameBox(tree.node(n).cell, cells[n])) << "node " << n;
    }
    EXPECT_EQ(tree.stats().splits + tree.stats().merges + tree.stats().root_growths, 0u);
    expectTreeInvariants(tree);
}

TEST(BspAdaptation, ALongRunOfMoversKeepsTheTreeSmallAndTheObjectsInLeaves) {
    // The default scenario's field with a fifth of it bouncing inside the field for 2000
    // frames: memory stays flat, objects stay in leaves, leaves within the limit.
    Field field(1500, 6);
    BspTree& tree = field.tree;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> speed(-0.2f, 0.2f);
    std::vector<glm::vec3> velocity(300);
    for (glm::vec3& v : velocity) v = glm::vec3(speed(rng), 0.25f * speed(rng), 3.0f * speed(rng));
    const glm::vec3 low(-35, 0, -200), high(35, 10, 0);
    uint32_t most_early = 0, most_late = 0;
    for (int frame = 1; frame <= 2000; ++frame) {
        for (uint32_t o = 0; o < 300; ++o) {
            Aabb box = translated(field.boxes[o], velocity[o]);
            for (int axis = 0; axis < 3; ++axis) {
                if (box.min[axis] < low[axis] || box.max[axis] > high[axis]) {
                    velocity[o][axis] = -velocity[o][axis];
                    box = translated(field.boxes[o], velocity[o]);
                }
            }
            field.move(o, box);
        }
        tree.refitDirtyBounds();
        (frame <= 1000 ? most_early : most_late) =
            std::max(frame <= 1000 ? most_early : most_late, tree.nodeCount());
    }
    expectTreeInvariants(tree);
    expectLeavesWithinTheLimit(tree);
    EXPECT_LE(most_late, most_early + most_early / 10) << "the node array keeps growing";
    EXPECT_LE(objectsInInnerNodes(tree), tree.objectCount() / 50);
    EXPECT_GT(tree.stats().splits, 100u);
    EXPECT_GT(tree.stats().merges, 10u);
}

}  // namespace
}  // namespace occsim
