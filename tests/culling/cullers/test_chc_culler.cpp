// CHC (culling/cullers/chc_culler.h) on the scripted query device, and the traversal it shares with
// CHC++ and the per-object culler over scripted visibility: no OpenGL.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "culling/cullers/async_culler.h"
#include "culling/cullers/chc_culler.h"
#include "culling/cullers/chcpp_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/devices/approximate_device.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/scripted_query_device.h"
#include "scripted_frames.h"

namespace occsim {
namespace {

using testing::buildTree;
using testing::expectConservative;
using testing::FrameLog;
using testing::gridBoxes;
using testing::inFrustum;
using testing::makeFrame;
using testing::makeView;
using testing::overview;
using testing::randomBoxes;
using testing::randomVisibility;
using testing::runFrame;

// Random small boxes plus long bars across the whole field, which straddle split planes and so
// stay in inner nodes.
std::vector<Aabb> boxesWithStraddlers(uint32_t* first_bar, uint32_t bars = 12) {
    std::vector<Aabb> boxes = randomBoxes(400, 17);
    *first_bar = static_cast<uint32_t>(boxes.size());
    for (uint32_t i = 0; i < bars; ++i) {
        const float z = -95.0f + 190.0f * static_cast<float>(i) / static_cast<float>(bars - 1);
        const bool along_x = i % 2 == 0;
        const glm::vec3 lo = along_x ? glm::vec3(-99, 0, z) : glm::vec3(z, 0, -99);
        const glm::vec3 hi = along_x ? glm::vec3(99, 2, z + 1) : glm::vec3(z + 1, 2, 99);
        boxes.push_back({lo, hi});
    }
    return boxes;
}

// The scripted device's answer for a query on `box`: does any visible object overlap it?
bool scriptedVisible(const Aabb& box, const std::vector<Aabb>& boxes,
                     const std::vector<uint8_t>& visible) {
    for (size_t o = 0; o < boxes.size(); ++o) {
        if (visible[o] && overlaps(box, boxes[o])) return true;
    }
    return false;
}

// The termination nodes of a settled CHC traversal (whole tree in the frustum, no straddlers):
// the largest invisible nodes below visible parents, and the visible leaves.
uint32_t terminationNodes(const BspTree& tree, uint32_t node, const std::vector<Aabb>& boxes,
                          const std::vector<uint8_t>& visible, uint32_t* visible_leaves) {
    const BspNode& n = tree.node(node);
    if (isEmpty(n.bounds)) return 0;
    const bool vis = scriptedVisible(n.bounds, boxes, visible);
    if (!vis) return 1;
    if (n.isLeaf()) {
        ++*visible_leaves;
        return 1;
    }
    return terminationNodes(tree, n.child[0], boxes, visible, visible_leaves) +
           terminationNodes(tree, n.child[1], boxes, visible, visible_leaves);
}

// The settled classification is a fixed point only if a visible node always has something
// visible below it, i.e. no visible object outside a subtree overlaps the subtree's bounds.
void expectConsistentScene(const BspTree& tree, const std::vector<Aabb>& boxes,
                           const std::vector<uint8_t>& visible) {
    for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
        const BspNode& node = tree.node(n);
        ASSERT_TRUE(node.isLeaf() || node.object_count == 0) << "straddler in node " << n;
        if (node.isLeaf() || isEmpty(node.bounds)) continue;
        if (!scriptedVisible(node.bounds, boxes, visible)) continue;
        const bool below = scriptedVisible(tree.bounds(node.child[0]), boxes, visible) ||
                           scriptedVisible(tree.bounds(node.child[1]), boxes, visible);
        ASSERT_TRUE(below) << "node " << n << " is visible with nothing visible below it";
    }
}

class ChcSettling : public ::testing::TestWithParam<uint32_t> {};

// A static scene: after the first frames CHC queries exactly the termination nodes of the
// previous frame, the visible leaves and the largest invisible nodes, and no opened node.
TEST_P(ChcSettling, AStaticSceneSettlesToQueryingOnlyTheTerminationNodes) {
    const uint32_t latency = GetParam();
    const std::vector<Aabb> boxes = gridBoxes(12, 12);
    const BspTree tree = buildTree(boxes, 1, BspSplitRule::Sah);
    std::mt19937 rng(5);
    const std::vector<uint8_t> visible = randomVisibility(boxes.size(), 0.1, rng);
    expectConsistentScene(tree, boxes, visible);
    const CullView view = overview(boxes);
    ASSERT_EQ(inFrustum(boxes, view.frustum).size(), boxes.size());

    uint32_t visible_leaves = 0;
    const uint32_t boundary = terminationNodes(tree, tree.root(), boxes, visible, &visible_leaves);
    ASSERT_GT(visible_leaves, 3u);
    ASSERT_GT(boundary, visible_leaves + 3);

    ChcCuller chc;
    chc.reset(tree);
    ScriptedQueryDevice device(latency);
    for (uint64_t f = 0; f < 6; ++f) {
        const FrameLog log = runFrame(chc, tree, device, boxes, visible, view, f);
        expectConservative(log, boxes, visible, view, "frame " + std::to_string(f));
        if (f >= 2) {
            EXPECT_EQ(log.queries, boundary) << "frame " << f;
        }
    }

    // With visible leaves assumed visible for two frames, each is queried once every third
    // frame, and the invisible termination nodes every frame.
    ChcOptions skip;
    skip.visible_frames_skip = 2;
    ChcCuller skipping(skip);
    skipping.reset(tree);
    uint64_t queries = 0;
    for (uint64_t f = 0; f < 12; ++f) {
        const FrameLog log = runFrame(skipping, tree, device, boxes, visible, view, f);
        expectConservative(log, boxes, visible, view, "skip frame " + std::to_string(f));
        if (f >= 3 && f < 12) queries += log.queries;
    }
    const uint32_t invisible_nodes = boundary - visible_leaves;
    EXPECT_EQ(queries, 9u * invisible_nodes + 3u * visible_leaves);
}

INSTANTIATE_TEST_SUITE_P(Latencies, ChcSettling, ::testing::Values(0u, 3u, 1000u));

class ConservativeTraversal : public ::testing::TestWithParam<std::tuple<std::string, uint32_t>> {};

// Over frames with visibility changing at random, a turning camera and any query latency, the
// statistical cullers, CHC and CHC++ (threshold 0) draw every visible object in the frustum,
// nothing outside it, nothing twice, and answer every query within its frame.
TEST_P(ConservativeTraversal, DrawsEveryObjectTheScriptedVisibilitySaysIsVisible) {
    const auto& [algorithm, latency] = GetParam();
    const std::vector<Aabb> boxes = randomBoxes(1500, 7);
    const BspTree tree = buildTree(boxes);
    CullerOptions options;
    OptionValues& chcpp = options.edit(*findCuller("chc++"));
    if (algorithm == "chc++ box") chcpp.set("tight_bounds_depth", 0);
    if (algorithm == "chc++ skip") chcpp.set("visible_frames_skip", 10);
    if (algorithm == "chc++ single") chcpp.set("multiqueries", 0);
    if (algorithm == "chc skip") options.edit(*findCuller("chc")).set("visible_frames_skip", 3);
    const std::string name = algorithm.substr(0, algorithm.find(' '));
    const std::unique_ptr<Culler> culler = testing::cullerNamed(name, options);
    culler->reset(tree);
    ScriptedQueryDevice device(latency);
    std::mt19937 rng(11);
    uint64_t total_queries = 0;
    std::vector<uint8_t> visible;
    for (uint32_t f = 0; f < 60; ++f) {
        const float a = 0.05f * static_cast<float>(f);
        const CullView view = makeView({0, 5, 0}, {100 * std::cos(a), 0, 100 * std::sin(a)});
        // Runs of frames with the same visibility, so that coherence has something to use.
        if (f % 4 == 0) visible = randomVisibility(boxes.size(), 0.15, rng);
        const FrameLog log = runFrame(*culler, tree, device, boxes, visible, view, f);
        expectConservative(log, boxes, visible, view, algorithm + " frame " + std::to_string(f));
        EXPECT_EQ(device.pendingQueries(), 0u) << "every query is answered within its frame";
        total_queries += log.queries;
    }
    EXPECT_GT(total_queries, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    CullersAndLatencies, ConservativeTraversal,
    ::testing::Combine(::testing::Values("statistical", "statistical+", "chc", "chc skip", "chc++",
                                         "chc++ box", "chc++ skip", "chc++ single"),
                       ::testing::Values(0u, 3u, 1000u)),
    [](const ::testing::TestParamInfo<ConservativeTraversal::ParamType>& param_info) {
        std::string name = std::get<0>(param_info.param) + "_latency" +
                           std::to_string(std::get<1>(param_info.param));
        for (char& c : name) {
            if (c == '+') c = 'p';
            if (c == ' ') c = '_';
        }
        return name;
    });

// Pull-up: when the only visible object moves from one half of the field to the other, the
// nodes above the newly visible one (the root among them, though the child it was visible
// through turned invisible) end the frame visible; the old half ends it invisible.
TEST(ChcCuller, PullUpMakesTheAncestorsOfANewlyVisibleNodeVisible) {
    const std::vector<Aabb> boxes = gridBoxes(8, 8);
    const BspTree tree = buildTree(boxes, 1, BspSplitRule::Sah);
    const CullView view = overview(boxes);
    const uint32_t a = 0;
    const uint32_t b = static_cast<uint32_t>(boxes.size() - 1);
    // a and b lie in different children of the root.
    uint32_t leaf_a = tree.nodeOf(a), leaf_b = tree.nodeOf(b);
    auto childOfRootAbove = [&](uint32_t node) {
        while (tree.node(node).parent != tree.root()) node = tree.node(node).parent;
        return node;
    };
    ASSERT_NE(childOfRootAbove(leaf_a), childOfRootAbove(leaf_b));

    ChcCuller chc;
    chc.reset(tree);
    ScriptedQueryDevice device(3);
    std::vector<uint8_t> visible(boxes.size(), 0);
    visible[a] = 1;
    for (uint64_t f = 0; f < 3; ++f) runFrame(chc, tree, device, boxes, visible, view, f);
    EXPECT_TRUE(chc.classifiedVisible(childOfRootAbove(leaf_a)));
    EXPECT_FALSE(chc.classifiedVisible(childOfRootAbove(leaf_b)));
    EXPECT_FALSE(chc.visitedLastFrame(leaf_b)) << "inside a culled subtree";

    visible[a] = 0;
    visible[b] = 1;
    const FrameLog log = runFrame(chc, tree, device, boxes, visible, view, 3);
    expectConservative(log, boxes, visible, view, "switch frame");
    for (uint32_t n = leaf_b; n != BspTree::kNone; n = tree.node(n).parent) {
        EXPECT_TRUE(chc.classifiedVisible(n)) << "ancestor " << n << " of the visible leaf";
    }
    EXPECT_FALSE(chc.classifiedVisible(childOfRootAbove(leaf_a)));
    EXPECT_FALSE(chc.classifiedVisible(leaf_a));
}

// A visible leaf is rendered at once and its query only updates the classification: the frame
// it turns invisible it is still drawn; the next frame it is not.
TEST(ChcCuller, APreviouslyVisibleLeafIsRenderedWithoutWaitingAndReclassifiedForTheNextFrame) {
    const std::vector<Aabb> boxes = gridBoxes(4, 4);
    const BspTree tree = buildTree(boxes, 1, BspSplitRule::Sah);
    const CullView view = overview(boxes);
    ChcCuller chc;
    chc.reset(tree);
    ScriptedQueryDevice device(1000);
    std::vector<uint8_t> visible(boxes.size(), 1);
    runFrame(chc, tree, device, boxes, visible, view, 0);
    FrameLog log = runFrame(chc, tree, device, boxes, visible, view, 1);
    EXPECT_EQ(log.drawn.size(), boxes.size());
    std::fill(visible.begin(), visible.end(), 0);
    log = runFrame(chc, tree, device, boxes, visible, view, 2);
    EXPECT_EQ(log.drawn.size(), boxes.size()) << "drawn on the assumption, then reclassified";
    log = runFrame(chc, tree, device, boxes, visible, view, 3);
    EXPECT_TRUE(log.drawn.empty());
    EXPECT_EQ(log.queries, 1u) << "the invisible leaves were pulled up into the root";
}

// Approximate visibility: a node whose query passes at most the threshold counts as occluded,
// so a visible object may be dropped. Not conservative, by design.
TEST(ChcCuller, AThresholdAboveZeroCullsNodesWithFewVisibleSamples) {
    const std::vector<Aabb> boxes = gridBoxes(4, 4);
    const BspTree tree = buildTree(boxes, 1, BspSplitRule::Sah);
    const CullView view = overview(boxes);
    std::vector<uint8_t> visible(boxes.size(), 0);
    visible[5] = 1;  // one object: every query on it passes one "sample"
    ChcCuller chc_exact, chc_approx;
    chc_exact.reset(tree);
    chc_approx.reset(tree);
    ScriptedQueryDevice device(0), approximated(0);
    ApproximateDevice threshold(approximated, ApproximationOptions{1, false});
    for (uint64_t f = 0; f < 3; ++f) {
        EXPECT_EQ(runFrame(chc_exact, tree, device, boxes, visible, view, f).drawn,
                  std::vector<uint32_t>{5});
        approximated.setVisibility(visible, boxes);
        chc_approx.cullAndRender(tree, makeFrame(view, f, f / 30.0), threshold);
        EXPECT_TRUE(approximated.drawnObjects().empty());
        approximated.clearLog();
    }
}

class InnerNodeObjects : public ::testing::TestWithParam<std::tuple<std::string, uint32_t>> {};

TEST_P(InnerNodeObjects, AreDrawnWheneverTheyAreVisible) {
    const auto& [name, latency] = GetParam();
    uint32_t first_bar = 0;
    const std::vector<Aabb> boxes = boxesWithStraddlers(&first_bar);
    const BspTree tree = buildTree(boxes);
    uint32_t in_inner_nodes = 0;
    for (uint32_t o = first_bar; o < boxes.size(); ++o) {
        in_inner_nodes += tree.node(tree.nodeOf(o)).isLeaf() ? 0 : 1;
    }
    ASSERT_GE(in_inner_nodes, 6u) << "the bars must straddle split planes";

    const std::unique_ptr<Culler> culler = testing::cullerNamed(name, CullerOptions{});
    culler->reset(tree);
    ScriptedQueryDevice device(latency);
    std::mt19937 rng(23);
    std::vector<uint8_t> visible;
    for (uint32_t f = 0; f < 40; ++f) {
        if (f % 5 == 0) {
            visible = randomVisibility(boxes.size(), 0.1, rng);
            // Bars alone: visible bars with nothing visible in the subtrees below them.
            for (uint32_t o = 0; o < first_bar; ++o) visible[o] = (f / 5) % 2 == 0 ? visible[o] : 0;
            for (uint32_t o = first_bar; o < boxes.size(); ++o) visible[o] = (o + f / 5) % 3 != 0;
        }
        const float a = 0.08f * static_cast<float>(f);
        const CullView view = makeView({0, 8, 0}, {100 * std::cos(a), 0, 100 * std::sin(a)});
        const FrameLog log = runFrame(*culler, tree, device, boxes, visible, view, f);
        expectConservative(log, boxes, visible, view, name + " frame " + std::to_string(f));
    }
}

INSTANTIATE_TEST_SUITE_P(
    Cullers, InnerNodeObjects,
    ::testing::Values(std::make_tuple("chc", 0u), std::make_tuple("chc", 3u),
                      std::make_tuple("chc", 1000u), std::make_tuple("chc++", 0u),
                      std::make_tuple("chc++", 3u), std::make_tuple("chc++", 1000u),
                      // The asynchronous culler is conservative only when results come at once.
                      std::make_tuple("async", 0u)),
    [](const ::testing::TestParamInfo<InnerNodeObjects::ParamType>& param_info) {
        std::string name = std::get<0>(param_info.param) + "_latency" +
                           std::to_string(std::get<1>(param_info.param));
        for (char& c : name) c = c == '+' ? 'p' : c;
        return name;
    });

// With tight bounds an opened node whose straddlers are the only visible objects keeps them
// drawn; also with tight bounds the straddlers of inner nodes are inside the query boxes.
TEST(InnerNodeObjects, ChcppTightBoundsCoverTheStraddlersOfEveryLevel) {
    uint32_t first_bar = 0;
    const std::vector<Aabb> boxes = boxesWithStraddlers(&first_bar);
    const BspTree tree = buildTree(boxes);
    ChcppOptions options;
    options.tight_bounds_depth = 3;
    ChcppCuller culler(options);
    culler.reset(tree);
    ScriptedQueryDevice device(2);
    std::vector<uint8_t> visible(boxes.size(), 0);
    for (uint32_t o = first_bar; o < boxes.size(); ++o) visible[o] = 1;  // only the bars
    const CullView view = makeView({0, 40, 150}, {0, 0, 0});
    for (uint64_t f = 0; f < 5; ++f) {
        const FrameLog log = runFrame(culler, tree, device, boxes, visible, view, f);
        expectConservative(log, boxes, visible, view, "frame " + std::to_string(f));
    }
}

}  // namespace
}  // namespace occsim
