// CHC, CHC++ and the per-object asynchronous culler on the scripted query device: no OpenGL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <memory>
#include <new>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "culling/cullers/async_culler.h"
#include "culling/cullers/chc_culler.h"
#include "culling/cullers/chcpp_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/devices/approximate_device.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

using testing::gridBoxes;
using testing::makeFrame;
using testing::makeView;
using testing::overview;
using testing::randomBoxes;
using testing::randomVisibility;

using testing::buildTree;
using testing::inFrustum;

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

// What a frame did, read from the scripted device's log.
struct FrameLog {
    std::vector<uint32_t> drawn;
    uint64_t queries = 0;
    uint64_t waited = 0;
};

FrameLog runFrame(Culler& culler, const BspTree& tree, ScriptedQueryDevice& device,
                  const std::vector<Aabb>& boxes, const std::vector<uint8_t>& visible,
                  const CullView& view, uint64_t frame) {
    device.setVisibility(visible, boxes);
    device.clearLog();
    device.resetCounters();
    culler.cullAndRender(tree, makeFrame(view, frame, static_cast<double>(frame) / 30.0), device);
    return {device.drawnObjects(), device.counters().queries_issued,
            device.counters().results_waited};
}

// Every object in the frustum that the script says is visible is drawn, nothing outside the
// frustum is, and nothing twice.
void expectConservative(const FrameLog& log, const std::vector<Aabb>& boxes,
                        const std::vector<uint8_t>& visible, const CullView& view,
                        const std::string& what) {
    const std::set<uint32_t> frustum = inFrustum(boxes, view.frustum);
    std::set<uint32_t> drawn;
    for (uint32_t o : log.drawn) {
        EXPECT_TRUE(drawn.insert(o).second) << what << ": object " << o << " drawn twice";
        EXPECT_TRUE(frustum.count(o)) << what << ": object " << o << " drawn outside the frustum";
    }
    for (uint32_t o : frustum) {
        if (visible[o]) {
            EXPECT_TRUE(drawn.count(o)) << what << ": visible object " << o << " missed";
        }
    }
}

// --- Brute force over the scripted visibility ---------------------------------------------------

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

// --- Options and the factory --------------------------------------------------------------------

TEST(PeerCullerOptions, DefaultsAreValidAndOutOfRangeValuesAreRejectedWithAMessage) {
    for (const char* name : {"chc", "chc++", "async"}) {
        const AlgorithmTraits& a = *findAlgorithm(name);
        EXPECT_EQ(checkOptionValues(a, OptionValues(a.options)), "") << name;
    }
    EXPECT_EQ(OptionValues(findAlgorithm("chc++")->options).count("batch_size"),
              ChcppOptions{}.batch_size);
    EXPECT_EQ(ChcppOptions{}.batch_size, 50u);
    EXPECT_EQ(AsyncOptions{}.retest_interval_frames, 5u);

    const auto rejects = [](const char* culler, const char* key, double value) {
        const AlgorithmTraits& a = *findAlgorithm(culler);
        OptionValues v(a.options);
        v.set(key, value);
        const std::string why = checkOptionValues(a, v);
        EXPECT_EQ(why.rfind(key, 0), 0u) << culler << " " << key << ": " << why;
    };
    rejects("chc", "visible_frames_skip", 2000000);
    rejects("chc++", "batch_size", 0);
    rejects("chc++", "tight_bounds_depth", 7);
    rejects("chc++", "multiqueries", 0.5);
    rejects("async", "retest_interval_frames", 0);
}

TEST(PeerCullerOptions, TheFactoryKnowsTheThreeByName) {
    const std::vector<std::string>& names = algorithmNames();
    for (const char* name : {"chc", "chc++", "async"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
        const std::unique_ptr<Culler> culler = testing::cullerNamed(name, CullerOptions{});
        ASSERT_NE(culler, nullptr) << name;
        EXPECT_EQ(culler->name(), name);
    }
}

// What each algorithm is comes from its registration, and every registered culler reports the
// name it was registered under.
TEST(AlgorithmRegistry, StatesWhatEachAlgorithmIs) {
    for (const AlgorithmTraits* a_row : algorithms()) {
        const AlgorithmTraits& a = *a_row;
        EXPECT_EQ(makeCuller(a, CullerOptions{})->name(), a.name);
        EXPECT_EQ(findAlgorithm(a.name), &a);
        EXPECT_FALSE(a.oracle && a.issues_queries) << a.name;
    }
    EXPECT_EQ(findAlgorithm("nope"), nullptr);
    EXPECT_TRUE(findAlgorithm("vfc")->speedup_reference);
    EXPECT_EQ(speedupReference().name, "vfc");
    EXPECT_TRUE(findAlgorithm("ideal")->oracle);
    EXPECT_FALSE(findAlgorithm("async")->conservative);
    for (const char* name : {"stop-and-wait", "statistical", "statistical+", "chc", "chc++"}) {
        EXPECT_TRUE(findAlgorithm(name)->conservative) << name;
        EXPECT_TRUE(findAlgorithm(name)->issues_queries) << name;
    }
}

// --- CHC ----------------------------------------------------------------------------------------

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
    OptionValues& chcpp = options.edit(*findAlgorithm("chc++"));
    if (algorithm == "chc++ box") chcpp.set("tight_bounds_depth", 0);
    if (algorithm == "chc++ skip") chcpp.set("visible_frames_skip", 10);
    if (algorithm == "chc++ single") chcpp.set("multiqueries", 0);
    if (algorithm == "chc skip") options.edit(*findAlgorithm("chc")).set("visible_frames_skip", 3);
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

// --- Objects stored in inner nodes, for all three -----------------------------------------------

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

// --- CHC++ --------------------------------------------------------------------------------------

// A row of cubes, one leaf each, so the invisible termination nodes are a handful of siblings
// along the path to the one visible cube.
struct RowScene {
    std::vector<Aabb> boxes = gridBoxes(8, 1);
    BspTree tree = buildTree(boxes, 1, BspSplitRule::Sah);
    CullView view = overview(boxes);
    std::vector<uint8_t> visible = std::vector<uint8_t>(boxes.size(), 0);
};

// A device that logs each query's boxes, in order, around the scripted device.
class QueryLoggingDevice final : public RenderDevice {
  public:
    explicit QueryLoggingDevice(ScriptedQueryDevice& inner) : inner_(inner) {}
    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override { inner_.drawObject(object); }
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> tags) override {
        queries.emplace_back(boxes.begin(), boxes.end());
        return inner_.issueQuery(boxes, tags);
    }
    bool isQueryReady(QueryId id) override { return inner_.isQueryReady(id); }
    QueryAnswer takeAnswer(QueryId id) override { return inner_.takeAnswer(id); }
    std::vector<std::vector<Aabb>> queries;

  private:
    ScriptedQueryDevice& inner_;
};

bool sameBox(const Aabb& a, const Aabb& b) { return a.min == b.min && a.max == b.max; }

TEST(ChcppCuller, AMultiqueryThatReturnsZeroKeepsAllItsNodesInvisibleWithOneQuery) {
    RowScene s;
    s.visible[0] = 1;
    ChcppOptions options;
    options.visible_frames_skip = 0;  // the visible leaf is queried every frame
    options.tight_bounds_depth = 0;   // one box per node
    ChcppCuller culler(options);
    culler.reset(s.tree);
    ScriptedQueryDevice device(0);
    for (uint64_t f = 0; f < 5; ++f) {
        runFrame(culler, s.tree, device, s.boxes, s.visible, s.view, f);
    }

    std::vector<uint32_t> invisible;  // the invisible termination nodes
    for (uint32_t n = 0; n < s.tree.nodeCount(); ++n) {
        if (culler.visitedLastFrame(n) && !culler.classifiedVisible(n)) invisible.push_back(n);
    }
    ASSERT_GE(invisible.size(), 2u);
    ASSERT_LE(invisible.size(), 4u);

    QueryLoggingDevice logging(device);
    device.setVisibility(s.visible, s.boxes);
    device.clearLog();
    device.resetCounters();
    culler.cullAndRender(s.tree, makeFrame(s.view, 5, 5 / 30.0), logging);
    EXPECT_EQ(culler.frameStats().multiqueries, 1u);
    EXPECT_EQ(culler.frameStats().multiquery_nodes, invisible.size());
    EXPECT_EQ(culler.frameStats().failed_multiqueries, 0u);
    EXPECT_EQ(device.counters().queries_issued, 2u) << "one multiquery and the visible leaf";
    EXPECT_EQ(device.counters().query_boxes, invisible.size() + 1);
    for (uint32_t n : invisible) EXPECT_FALSE(culler.classifiedVisible(n));
    EXPECT_EQ(device.drawnObjects(), std::vector<uint32_t>{0});
}

TEST(ChcppCuller, AMultiqueryThatFindsSomethingFallsBackToAQueryForEachNode) {
    RowScene s;
    s.visible[0] = 1;
    ChcppOptions options;
    options.visible_frames_skip = 0;
    options.tight_bounds_depth = 0;
    ChcppCuller culler(options);
    culler.reset(s.tree);
    ScriptedQueryDevice device(0);
    for (uint64_t f = 0; f < 5; ++f) {
        runFrame(culler, s.tree, device, s.boxes, s.visible, s.view, f);
    }
    std::vector<uint32_t> invisible;
    for (uint32_t n = 0; n < s.tree.nodeCount(); ++n) {
        if (culler.visitedLastFrame(n) && !culler.classifiedVisible(n)) invisible.push_back(n);
    }

    s.visible[7] = 1;  // the far end of the row, inside one of the invisible nodes
    QueryLoggingDevice logging(device);
    device.setVisibility(s.visible, s.boxes);
    device.clearLog();
    culler.cullAndRender(s.tree, makeFrame(s.view, 5, 5 / 30.0), logging);
    EXPECT_EQ(culler.frameStats().multiqueries, 1u);
    EXPECT_EQ(culler.frameStats().failed_multiqueries, 1u);
    // Each node of the failed group is queried again on its own, with its own box.
    for (uint32_t n : invisible) {
        int alone = 0;
        for (const auto& q : logging.queries) {
            alone += q.size() == 1 && sameBox(q[0], s.tree.bounds(n)) ? 1 : 0;
        }
        EXPECT_EQ(alone, 1) << "node " << n;
    }
    const std::set<uint32_t> drawn(device.drawnObjects().begin(), device.drawnObjects().end());
    EXPECT_EQ(drawn, (std::set<uint32_t>{0, 7}));
}

TEST(ChcppCuller, BatchesQueriesOfPreviouslyInvisibleNodes) {
    const std::vector<Aabb> boxes = randomBoxes(1500, 3);
    const BspTree tree = buildTree(boxes);
    std::mt19937 rng(4);
    const std::vector<uint8_t> visible = randomVisibility(boxes.size(), 0.1, rng);
    const CullView view = makeView({0, 5, 0}, {0, 0, -100});
    auto changes = [&](uint32_t batch_size, uint32_t* batches) {
        ChcppOptions options;
        options.batch_size = batch_size;
        ChcppCuller culler(options);
        culler.reset(tree);
        ScriptedQueryDevice device(4);
        runFrame(culler, tree, device, boxes, visible, view, 0);
        *batches = culler.frameStats().query_batches;
        return culler.frameStats().state_changes;
    };
    uint32_t batches_1 = 0, batches_50 = 0;
    const uint32_t changes_1 = changes(1, &batches_1);
    const uint32_t changes_50 = changes(50, &batches_50);
    EXPECT_LT(batches_50, batches_1);
    EXPECT_LT(changes_50, changes_1);
}

// Nodes that turn visible together are first re-tested after random intervals in [0, n_av), the
// same in every run with the same seed.
TEST(ChcppCuller, TheRandomisedRetestIsSpreadAndTheSameInEveryRun) {
    const std::vector<Aabb> boxes = gridBoxes(10, 10);
    const BspTree tree = buildTree(boxes, 1, BspSplitRule::Sah);
    const CullView view = overview(boxes);
    ChcppOptions options;
    options.visible_frames_skip = 8;
    std::vector<std::vector<uint64_t>> runs;
    std::vector<std::vector<std::vector<uint32_t>>> drawn_runs;
    for (int run = 0; run < 2; ++run) {
        ChcppCuller culler(options);
        culler.reset(tree);
        ScriptedQueryDevice device(3);
        std::mt19937 vis_rng(9);
        std::vector<std::vector<uint32_t>> drawn;
        std::vector<uint8_t> visible = randomVisibility(boxes.size(), 0.5, vis_rng);
        for (uint64_t f = 0; f < 30; ++f) {
            if (f % 10 == 9) visible = randomVisibility(boxes.size(), 0.5, vis_rng);
            const FrameLog log = runFrame(culler, tree, device, boxes, visible, view, f);
            expectConservative(log, boxes, visible, view, "frame " + std::to_string(f));
            drawn.push_back(log.drawn);
            if (f == 0) {
                std::vector<uint64_t> next;
                for (uint32_t o = 0; o < boxes.size(); ++o) {
                    if (visible[o]) next.push_back(culler.nextQueryFrame(tree.nodeOf(o)));
                }
                runs.push_back(next);
            }
        }
        drawn_runs.push_back(drawn);
    }
    EXPECT_EQ(runs[0], runs[1]);
    EXPECT_EQ(drawn_runs[0], drawn_runs[1]);
    const std::set<uint64_t> distinct(runs[0].begin(), runs[0].end());
    EXPECT_GE(distinct.size(), 5u) << "first re-tests spread over the frames";
    for (uint64_t next : runs[0]) {
        EXPECT_GE(next, 1u);
        EXPECT_LE(next, 8u) << "first re-test after r < n_av frames of assumed visibility";
    }

    // Another seed spreads them differently.
    options.seed = 2;
    ChcppCuller other(options);
    other.reset(tree);
    ScriptedQueryDevice device(3);
    std::mt19937 vis_rng(9);
    const std::vector<uint8_t> visible = randomVisibility(boxes.size(), 0.5, vis_rng);
    runFrame(other, tree, device, boxes, visible, view, 0);
    std::vector<uint64_t> next;
    for (uint32_t o = 0; o < boxes.size(); ++o) {
        if (visible[o]) next.push_back(other.nextQueryFrame(tree.nodeOf(o)));
    }
    EXPECT_NE(next, runs[0]);
}

// --- The asynchronous per-object culler ---------------------------------------------------------

// A device that records every command (draw or query) in order, with its frame, around the
// scripted device: the test can then tell exactly when a query's result becomes ready.
class CommandLoggingDevice final : public RenderDevice {
  public:
    struct Command {
        uint64_t frame;
        bool query;
        uint32_t object;  // drawn object, or the object whose box was queried
    };
    CommandLoggingDevice(ScriptedQueryDevice& inner, const std::vector<Aabb>& boxes)
        : inner_(inner), boxes_(boxes) {}
    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override {
        log.push_back({frame, false, object});
        inner_.drawObject(object);
    }
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> tags) override {
        uint32_t object = UINT32_MAX;
        for (uint32_t o = 0; o < boxes_.size(); ++o) {
            if (boxes.size() == 1 && sameBox(boxes[0], boxes_[o])) object = o;
        }
        log.push_back({frame, true, object});
        return inner_.issueQuery(boxes, tags);
    }
    bool isQueryReady(QueryId id) override { return inner_.isQueryReady(id); }
    QueryAnswer takeAnswer(QueryId id) override {
        const QueryAnswer answer = inner_.takeAnswer(id);
        EXPECT_FALSE(answer.waited) << "the asynchronous culler never waits";
        return answer;
    }
    std::vector<Command> log;
    uint64_t frame = 0;

  private:
    ScriptedQueryDevice& inner_;
    const std::vector<Aabb>& boxes_;
};

// A row of cubes seen from one end: object X, the nearest, is occluded until frame `appear`;
// the fillers behind it are always visible. X is visited first in every frame, so an answer
// can arrive while the rest of the frame is drawn, after X was passed over.
struct AsyncScene {
    std::vector<Aabb> boxes = gridBoxes(6, 1);
    uint32_t x = 0;
    BspTree tree = buildTree(boxes, 1, BspSplitRule::Sah);
    CullView view = makeView({-10, 5, 5}, {8, 0, 0});
};

struct AsyncRun {
    std::vector<CommandLoggingDevice::Command> log;
    int64_t first_drawn = -1;  // first frame >= appear in which X was drawn
    std::vector<uint32_t> x_queries_per_frame;
};

AsyncRun runAsync(const AsyncScene& s, uint32_t latency, uint64_t appear, uint64_t frames,
                  uint32_t retest = 1000) {
    AsyncOptions options;
    options.retest_interval_frames = retest;
    AsyncCuller culler(options);
    culler.reset(s.tree);
    ScriptedQueryDevice scripted(latency);
    CommandLoggingDevice device(scripted, s.boxes);
    AsyncRun run;
    for (uint64_t f = 0; f < frames; ++f) {
        std::vector<uint8_t> visible(s.boxes.size(), 1);
        visible[s.x] = f >= appear ? 1 : 0;
        scripted.setVisibility(visible, s.boxes);
        device.frame = f;
        const size_t before = device.log.size();
        culler.cullAndRender(s.tree, makeFrame(s.view, f, f / 30.0), device);
        uint32_t x_queries = 0;
        for (size_t i = before; i < device.log.size(); ++i) {
            const auto& c = device.log[i];
            if (c.object != s.x) continue;
            if (c.query) ++x_queries;
            if (!c.query && f >= appear && run.first_drawn < 0) {
                run.first_drawn = static_cast<int64_t>(f);
            }
        }
        run.x_queries_per_frame.push_back(x_queries);
        EXPECT_LE(culler.pendingQueries(), s.boxes.size());
    }
    run.log = device.log;
    return run;
}

// The frame in which the answer to X's first query issued at or after `appear` becomes ready:
// the scripted device makes it ready once `latency` more commands have been submitted.
int64_t arrivalFrame(const AsyncRun& run, uint32_t x, uint64_t appear, uint32_t latency) {
    for (size_t i = 0; i < run.log.size(); ++i) {
        const auto& c = run.log[i];
        if (c.query && c.object == x && c.frame >= appear) {
            if (i + latency >= run.log.size()) return -1;
            return static_cast<int64_t>(run.log[i + latency].frame);
        }
    }
    return -1;
}

class AsyncLatency : public ::testing::TestWithParam<uint32_t> {};

TEST_P(AsyncLatency, ANewlyVisibleObjectIsDrawnInTheFrameItsQueryResultArrives) {
    const uint32_t latency = GetParam();
    AsyncScene s;
    ASSERT_EQ(inFrustum(s.boxes, s.view.frustum).size(), s.boxes.size());
    // Late enough for X's first answers (occluded) to have arrived: until then it is untested,
    // and drawn.
    const uint64_t appear = 20;
    const AsyncRun run = runAsync(s, latency, appear, 60);
    const int64_t arrival = arrivalFrame(run, s.x, appear, latency);
    ASSERT_GE(arrival, static_cast<int64_t>(appear));
    EXPECT_EQ(run.first_drawn, arrival) << "latency " << latency;
    if (latency == 0) {
        EXPECT_EQ(run.first_drawn, static_cast<int64_t>(appear));
    }
}

INSTANTIATE_TEST_SUITE_P(Latencies, AsyncLatency, ::testing::Values(0u, 1u, 3u, 7u, 12u, 40u));

// The error is real: with results in flight across frames, an object that appears behind an
// occluder is missing from the frames until its answer arrives.
TEST(AsyncCuller, MissesANewlyVisibleObjectWhileItsResultIsPending) {
    AsyncScene s;
    const uint64_t appear = 6;
    const uint32_t latency = 20;  // about three frames of commands
    const AsyncRun run = runAsync(s, latency, appear, 30);
    ASSERT_GT(run.first_drawn, static_cast<int64_t>(appear) + 1);
    for (const auto& c : run.log) {
        if (c.frame == appear) {
            EXPECT_FALSE(!c.query && c.object == s.x) << "drawn at once";
        }
    }
}

TEST(AsyncCuller, QueriesOccludedObjectsEveryFrameAndVisibleOnesEveryNFrames) {
    AsyncScene s;
    // Occluded all along: one query per frame, never drawn.
    AsyncRun run = runAsync(s, 0, 1000, 12, 5);
    for (uint64_t f = 0; f < 12; ++f) EXPECT_EQ(run.x_queries_per_frame[f], 1u) << f;
    EXPECT_EQ(run.first_drawn, -1);
    // Visible all along: queried in frames 0, 5, 10, 15, drawn every frame.
    run = runAsync(s, 0, 0, 17, 5);
    for (uint64_t f = 0; f < 17; ++f) {
        EXPECT_EQ(run.x_queries_per_frame[f], f % 5 == 0 ? 1u : 0u) << f;
    }
    EXPECT_EQ(run.first_drawn, 0);
}

// Every query id is collected eventually, without ever waiting, however late the results come.
TEST(AsyncCuller, CollectsEveryQueryWithoutWaiting) {
    const std::vector<Aabb> boxes = randomBoxes(600, 13);
    const BspTree tree = buildTree(boxes);
    for (uint32_t latency : {0u, 5u, 200u, 5000u}) {
        AsyncCuller culler;
        culler.reset(tree);
        ScriptedQueryDevice device(latency);
        std::mt19937 rng(2);
        uint64_t fetched = 0, issued = 0;
        for (uint32_t f = 0; f < 50; ++f) {
            const float a = 0.1f * static_cast<float>(f);
            const CullView view = makeView({0, 5, 0}, {100 * std::cos(a), 0, 100 * std::sin(a)});
            const std::vector<uint8_t> visible = randomVisibility(boxes.size(), 0.3, rng);
            const FrameLog log = runFrame(culler, tree, device, boxes, visible, view, f);
            EXPECT_EQ(log.waited, 0u) << "latency " << latency;
            fetched += device.counters().results_fetched;
            issued += log.queries;
            EXPECT_EQ(culler.pendingQueries(), device.pendingQueries());
            EXPECT_LE(device.pendingQueries(), boxes.size());
        }
        EXPECT_EQ(issued - fetched, device.pendingQueries()) << "latency " << latency;
        if (latency <= 200) {
            EXPECT_GT(fetched, issued / 2) << "latency " << latency;
        }
    }
}

TEST(AsyncCuller, DrawsAnObjectTheNearPlaneMayCutWithoutAQuery) {
    const std::vector<Aabb> boxes{{glm::vec3(-1, -1, -1), glm::vec3(1, 1, 1)}};
    const BspTree tree = buildTree(boxes);
    AsyncCuller culler;
    culler.reset(tree);
    ScriptedQueryDevice device(0);
    for (uint64_t f = 0; f < 3; ++f) {
        const CullView inside = makeView({0, 0, 0}, {0, 0, -5});
        const FrameLog log = runFrame(culler, tree, device, boxes, {0}, inside, f);
        EXPECT_EQ(log.drawn, std::vector<uint32_t>{0});
        EXPECT_EQ(log.queries, 0u);
    }
}

}  // namespace
}  // namespace occsim
