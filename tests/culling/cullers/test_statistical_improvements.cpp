// The improvements of statistical+ (culling/cullers/statistical_options.h), one at a time on the
// paper's options: each changes what it says on the scripted query device and stays conservative.
// No OpenGL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "culling/cullers/statistical_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

using testing::buildTree;
using testing::gridBoxes;
using testing::inFrustum;
using testing::makeFrame;
using testing::makeView;
using testing::overview;
using testing::randomBoxes;
using testing::randomVisibility;

// The paper's options with one improvement switched on.
StatisticalOptions paperWith(void (*on)(StatisticalOptions&)) {
    StatisticalOptions o;
    on(o);
    return o;
}

struct ScriptedFrame {
    std::vector<uint32_t> drawn;
    std::vector<QueryTag> queries;
    uint64_t waited = 0;
};

ScriptedFrame runScripted(Culler& culler, const BspTree& tree, ScriptedQueryDevice& device,
                          const std::vector<Aabb>& boxes, const std::vector<uint8_t>& visible,
                          const CullFrame& frame) {
    device.setVisibility(visible, boxes);
    device.clearLog();
    device.resetCounters();
    culler.cullAndRender(tree, frame, device);
    return {device.drawnObjects(), device.queryTags(), device.counters().results_waited};
}

// Every object in the frustum that the script says is visible is drawn, nothing twice.
void expectConservative(const ScriptedFrame& f, const std::vector<Aabb>& boxes,
                        const std::vector<uint8_t>& visible, const CullView& view,
                        const std::string& what) {
    std::set<uint32_t> drawn;
    for (uint32_t o : f.drawn) EXPECT_TRUE(drawn.insert(o).second) << what << ": " << o << " twice";
    for (uint32_t o : inFrustum(boxes, view.frustum)) {
        if (visible[o]) {
            EXPECT_TRUE(drawn.count(o)) << what << ": visible object " << o << " missed";
        }
    }
}

// (1) Ready answers: the culler blocks on an answer only when nothing else can be done (its
// queue is empty, or queries_before_restart queries are in flight). The paper's loop blocks at
// the end of every pass on all answers, ready or not, with nodes still waiting in the queue.
TEST(StatisticalReadyAnswers, BlocksOnlyWhenTheQueueHoldsNothingElse) {
    const std::vector<Aabb> boxes = randomBoxes(1500, 7);
    const BspTree tree = buildTree(boxes);
    std::mt19937 rng(11);
    std::vector<uint8_t> visible;
    StatisticalCuller paper;
    StatisticalCuller ready(paperWith([](StatisticalOptions& o) { o.ready_answers = true; }));
    paper.reset(tree);
    ready.reset(tree);
    ScriptedQueryDevice paper_device(12), ready_device(12);
    uint64_t paper_blocked_with_work = 0, ready_blocked = 0, ready_waited = 0, paper_waited = 0;
    for (uint32_t f = 0; f < 40; ++f) {
        const float a = 0.05f * static_cast<float>(f);
        const CullView view = makeView({0, 5, 0}, {100 * std::cos(a), 0, 100 * std::sin(a)});
        if (f % 4 == 0) visible = randomVisibility(boxes.size(), 0.15, rng);
        const CullFrame frame = makeFrame(view, f, f / 30.0);
        const ScriptedFrame p = runScripted(paper, tree, paper_device, boxes, visible, frame);
        const ScriptedFrame r = runScripted(ready, tree, ready_device, boxes, visible, frame);
        expectConservative(r, boxes, visible, view, "frame " + std::to_string(f));
        EXPECT_EQ(ready.lastFrame().blocked_with_work_left, 0u) << "frame " << f;
        EXPECT_EQ(ready.lastFrame().blocked_answers, r.waited) << "the device saw every wait";
        EXPECT_EQ(ready_device.pendingQueries(), 0u) << "every answer taken within its frame";
        paper_blocked_with_work += paper.lastFrame().blocked_with_work_left;
        ready_blocked += ready.lastFrame().blocked_answers;
        ready_waited += r.waited;
        paper_waited += p.waited;
    }
    EXPECT_GT(paper_blocked_with_work, 0u) << "the paper's passes do block with work left";
    EXPECT_GT(ready_blocked, 0u) << "the test does make the culler wait";
    EXPECT_LT(ready_waited, paper_waited / 2);
}

// 1,500 random boxes, 5 % of them visible, and a camera turning on the spot: the scene of the
// tests of the bound on queries in flight. Answers on a ScriptedQueryDevice(200) arrive late, so
// the bound is what stops the culler issuing.
struct TurnOverSparseField {
    std::vector<Aabb> boxes = randomBoxes(1500, 7);
    BspTree tree = buildTree(boxes);
    std::vector<uint8_t> visible;
    TurnOverSparseField() {
        std::mt19937 rng(11);
        visible = randomVisibility(boxes.size(), 0.05, rng);
    }
    // Ready answers with a bound of 4 in flight: the tests' starting point.
    static StatisticalOptions boundedAt4() {
        StatisticalOptions o;
        o.ready_answers = true;
        o.queries_before_restart = 4;
        return o;
    }
    // Culls frame f of the turn and checks that everything visible was drawn.
    void runFrame(StatisticalCuller& culler, ScriptedQueryDevice& device, uint32_t f) const {
        const float a = 0.05f * static_cast<float>(f);
        const CullView view = makeView({0, 5, 0}, {100 * std::cos(a), 0, 100 * std::sin(a)});
        const ScriptedFrame r =
            runScripted(culler, tree, device, boxes, visible, makeFrame(view, f, f / 30.0));
        expectConservative(r, boxes, visible, view, "frame " + std::to_string(f));
    }
};

// (7) Weighed in-flight bound: with ready answers, queries whose kind mostly comes back occluded
// count for less than one against queries_before_restart, so more of them run ahead at once (at
// most kMaxRunAhead times the bound), while each query still counts as one without the option.
TEST(StatisticalWeighInFlight, QueriesLikelyOccludedRunFurtherAheadThanTheBound) {
    const TurnOverSparseField scene;
    uint32_t most_in_flight[2] = {0, 0};
    for (const bool weigh : {false, true}) {
        StatisticalOptions o = TurnOverSparseField::boundedAt4();
        o.weigh_in_flight = weigh;
        StatisticalCuller culler(o);
        culler.reset(scene.tree);
        ScriptedQueryDevice device(200);
        for (uint32_t f = 0; f < 20; ++f) {
            scene.runFrame(culler, device, f);
            EXPECT_EQ(device.pendingQueries(), 0u) << "every answer taken within its frame";
        }
        most_in_flight[weigh ? 1 : 0] = device.maxPendingQueries();
    }
    EXPECT_LE(most_in_flight[0], 4u) << "each query counts as one";
    EXPECT_GT(most_in_flight[1], 8u) << "queries likely occluded count for less";
    EXPECT_LE(most_in_flight[1], 4u * static_cast<uint32_t>(StatisticalOptions::kMaxRunAhead));
}

// (9) Waits per frame: with ready answers, the bound on queries in flight is the larger of
// queries_before_restart and the last frame's waited queries over waits_per_frame, so a frame of
// many queries lets more of them run ahead (on llvmpipe, where one wait makes every earlier
// answer ready, it blocks less often; the scripted device makes each answer wait on its own, so
// the test checks the bound and what is in flight); 0 keeps the fixed bound.
TEST(StatisticalWaitsPerFrame, TheBoundGrowsWithTheQueriesTheLastFrameWaitedFor) {
    const TurnOverSparseField scene;
    uint32_t most_in_flight[2] = {0, 0};
    for (const uint32_t waits : {0u, 4u}) {
        StatisticalOptions o = TurnOverSparseField::boundedAt4();
        o.waits_per_frame = waits;
        StatisticalCuller culler(o);
        culler.reset(scene.tree);
        ScriptedQueryDevice device(200);
        uint32_t last_waited = 0;  // every query is waited for (no draw_while_requerying)
        for (uint32_t f = 0; f < 20; ++f) {
            scene.runFrame(culler, device, f);
            const StatisticalFrameCounters& c = culler.lastFrame();
            const double expected = waits == 0 ? 4.0 : std::max(4.0, last_waited / 4.0);
            EXPECT_DOUBLE_EQ(c.in_flight_bound, expected) << "frame " << f;
            last_waited = c.queries;
        }
        most_in_flight[waits ? 1 : 0] = device.maxPendingQueries();
    }
    EXPECT_LE(most_in_flight[0], 4u) << "the fixed bound";
    EXPECT_GT(most_in_flight[1], 16u) << "a frame of many queries lets more run ahead";
}

// (8) Descend visible inner nodes: an inner node last found visible whose re-query is due is not
// queried; its children decide. Leaves are still re-queried, and the paper queries both.
TEST(StatisticalDescendVisibleInnerNodes, AVisibleInnerNodeDueForAQueryIsNotQueried) {
    const std::vector<Aabb> boxes = randomBoxes(300, 5);
    const BspTree tree = buildTree(boxes);
    const std::vector<uint8_t> visible(boxes.size(), 1);
    const CullView view = makeView({0, 5, 0}, {100, 0, 0});
    for (const bool descend : {false, true}) {
        StatisticalOptions o;
        o.ready_answers = true;
        o.base_time_s = 0.1;
        o.descend_visible_inner_nodes = descend;
        StatisticalCuller culler(o);
        culler.reset(tree);
        ScriptedQueryDevice device(4);
        runScripted(culler, tree, device, boxes, visible, makeFrame(view, 0, 0.0));
        // 0.5 s later every re-query is due (0.1 s * (2 - 0.5)).
        const ScriptedFrame f =
            runScripted(culler, tree, device, boxes, visible, makeFrame(view, 1, 0.5));
        expectConservative(f, boxes, visible, view, descend ? "descend" : "paper");
        uint32_t inner = 0, leaves = 0;
        for (const QueryTag& q : f.queries) {
            if (q.subject != QueryTag::Subject::Node) continue;
            (tree.node(q.index).isLeaf() ? leaves : inner) += 1;
        }
        EXPECT_GT(leaves, 0u) << "leaves are re-queried either way";
        if (descend) {
            EXPECT_EQ(inner, 0u) << "no visible inner node is re-queried";
            EXPECT_GT(culler.lastFrame().inner_descents, 0u);
        } else {
            EXPECT_GT(inner, 0u) << "the paper re-queries inner nodes too";
        }
    }
}

// (6) Draw while re-querying: a node last found visible whose re-query is due is drawn in the
// same pass as its query, and its answer, arriving late, only updates its statistics (in the next
// frame). The paper's culler waits for that answer before it draws.
TEST(StatisticalDrawWhileRequerying, AVisibleNodeDueForAQueryIsDrawnWithoutWaitingForTheAnswer) {
    const std::vector<Aabb> boxes{{glm::vec3(-1, -1, -11), glm::vec3(1, 1, -9)}};
    const BspTree tree = buildTree(boxes);
    const std::vector<uint8_t> visible{1};
    const CullView view = makeView({0, 0, 0}, {0, 0, -10});
    const auto options = [](bool draw) {
        StatisticalOptions o;
        o.ready_answers = true;
        o.base_time_s = 0.1;
        o.draw_while_requerying = draw;
        return o;
    };
    for (const bool draw : {false, true}) {
        StatisticalCuller culler(options(draw));
        culler.reset(tree);
        ScriptedQueryDevice device(1000);  // no answer is ready within a frame
        // Frame 0: no statistics, so the query is awaited either way.
        ScriptedFrame f =
            runScripted(culler, tree, device, boxes, visible, makeFrame(view, 0, 0.0));
        EXPECT_EQ(f.drawn, std::vector<uint32_t>{0});
        EXPECT_EQ(f.waited, 1u);
        // Frame 1, 0.5 s later: the re-query is due (0.1 s * (2 - 0.5)).
        f = runScripted(culler, tree, device, boxes, visible, makeFrame(view, 1, 0.5));
        EXPECT_EQ(f.drawn, std::vector<uint32_t>{0}) << "drawn either way: it is visible";
        ASSERT_EQ(f.queries.size(), 1u);
        if (!draw) {
            EXPECT_EQ(f.waited, 1u) << "the paper waits for the answer before it draws";
            EXPECT_EQ(culler.statistics(tree.root()).results, 2u);
            continue;
        }
        EXPECT_EQ(f.waited, 0u) << "drawn at once, the answer left in flight";
        EXPECT_EQ(culler.lastFrame().update_queries, 1u);
        EXPECT_EQ(device.pendingQueries(), 1u);
        EXPECT_EQ(culler.statistics(tree.root()).results, 1u) << "its answer has not come yet";
        // Frame 2: the late answer is taken first and goes into the statistics, with the time it
        // was asked at; the node is not due again.
        f = runScripted(culler, tree, device, boxes, visible, makeFrame(view, 2, 0.55));
        EXPECT_EQ(culler.statistics(tree.root()).results, 2u);
        EXPECT_DOUBLE_EQ(culler.statistics(tree.root()).last_query_time_s, 0.5);
        EXPECT_TRUE(f.queries.empty());
        EXPECT_EQ(f.drawn, std::vector<uint32_t>{0});
        EXPECT_EQ(device.pendingQueries(), 0u);
    }
}

// Bars lying across the whole field straddle the split planes and stay in inner nodes; small
// cubes above them fill the leaves.
struct BarsUnderCubes {
    std::vector<Aabb> boxes = gridBoxes(10, 10, 4.0f);
    uint32_t first_bar = 0;
    BarsUnderCubes() {
        first_bar = static_cast<uint32_t>(boxes.size());
        for (int i = 0; i < 6; ++i) {
            const float z = -2.0f - 5.0f * static_cast<float>(i);
            boxes.push_back({glm::vec3(-1, 0, z), glm::vec3(29, 1, z + 0.5f)});
        }
    }
};

// (2) Virtual leaves: objects stored in an inner node get a query of their own, on their boxes,
// and statistics of their own. Hidden bars stay undrawn, though every node above them is visible
// (a visible cube lies in each); the paper draws them with their node.
TEST(StatisticalVirtualLeaves, HiddenObjectsOfAVisibleInnerNodeAreQueriedNotDrawn) {
    const BarsUnderCubes scene;
    const BspTree tree = buildTree(scene.boxes, 4, BspSplitRule::Sah);
    std::vector<uint8_t> visible(scene.boxes.size(), 1);
    std::set<uint32_t> bar_nodes;
    for (uint32_t b = scene.first_bar; b < scene.boxes.size(); ++b) {
        visible[b] = 0;
        ASSERT_FALSE(tree.node(tree.nodeOf(b)).isLeaf()) << "bar " << b << " straddles a split";
        bar_nodes.insert(tree.nodeOf(b));
    }
    const CullView view = overview(scene.boxes);
    StatisticalCuller paper;
    StatisticalCuller leaves(paperWith([](StatisticalOptions& o) { o.virtual_leaves = true; }));
    paper.reset(tree);
    leaves.reset(tree);
    ScriptedQueryDevice device(3);
    for (uint64_t f = 0; f < 6; ++f) {
        const CullFrame frame = makeFrame(view, f, f / 30.0);
        const ScriptedFrame p = runScripted(paper, tree, device, scene.boxes, visible, frame);
        const ScriptedFrame v = runScripted(leaves, tree, device, scene.boxes, visible, frame);
        expectConservative(v, scene.boxes, visible, view, "frame " + std::to_string(f));
        uint32_t bars_paper = 0, bars_leaves = 0, own_queries = 0;
        for (uint32_t o : p.drawn) bars_paper += o >= scene.first_bar;
        for (uint32_t o : v.drawn) bars_leaves += o >= scene.first_bar;
        for (const QueryTag& t : v.queries)
            own_queries += t.subject == QueryTag::Subject::NodeObjects;
        EXPECT_EQ(bars_paper, 6u) << "frame " << f;
        EXPECT_EQ(bars_leaves, 0u) << "frame " << f;
        if (f == 0) {
            EXPECT_EQ(own_queries, bar_nodes.size());
        }
    }
    for (uint32_t n : bar_nodes) {
        const NodeStatistics& s = leaves.ownObjectStatistics(n);
        EXPECT_GT(s.results, 0u);
        EXPECT_EQ(s.history & 1u, 0u) << "last result: occluded";
        EXPECT_EQ(leaves.statistics(n).history & 1u, 1u) << "the node itself is visible";
    }
}

// (2b) Object queries: in a visible leaf, each object is decided on its own statistics, so once
// they have settled only the visible objects are drawn; the paper draws the whole leaf.
TEST(StatisticalObjectQueries, OnlyTheVisibleObjectsOfAVisibleLeafAreDrawn) {
    const std::vector<Aabb> boxes = gridBoxes(12, 12);
    const BspTree tree = buildTree(boxes, 4, BspSplitRule::Sah);
    std::mt19937 rng(5);
    const std::vector<uint8_t> visible = randomVisibility(boxes.size(), 0.25, rng);
    const CullView view = overview(boxes);
    StatisticalCuller paper;
    StatisticalCuller objects(paperWith([](StatisticalOptions& o) { o.object_queries = true; }));
    paper.reset(tree);
    objects.reset(tree);
    ScriptedQueryDevice device(3);
    std::set<uint32_t> visible_set;
    for (uint32_t o = 0; o < boxes.size(); ++o) {
        if (visible[o]) visible_set.insert(o);
    }
    for (uint64_t f = 0; f < 8; ++f) {
        const CullFrame frame = makeFrame(view, f, f / 30.0);
        const ScriptedFrame p = runScripted(paper, tree, device, boxes, visible, frame);
        const ScriptedFrame q = runScripted(objects, tree, device, boxes, visible, frame);
        expectConservative(q, boxes, visible, view, "frame " + std::to_string(f));
        uint32_t object_queries = 0;
        for (const QueryTag& t : q.queries)
            object_queries += t.subject == QueryTag::Subject::Object;
        EXPECT_GT(object_queries, 0u);
        if (f >= 2) {
            EXPECT_EQ(std::set<uint32_t>(q.drawn.begin(), q.drawn.end()), visible_set) << f;
            EXPECT_GT(p.drawn.size(), visible_set.size() + 20) << f;
        }
    }
}

uint64_t subtreeObjects(const BspTree& tree, uint32_t node) {
    uint64_t n = tree.node(node).object_count;
    if (!tree.node(node).isLeaf()) {
        n += subtreeObjects(tree, tree.node(node).child[0]) +
             subtreeObjects(tree, tree.node(node).child[1]);
    }
    return n;
}

// (3) Cost model, first rule: a node whose drawing costs less than one query box is drawn without
// a query, statistics or not; the nodes that are queried all cost more to draw.
TEST(StatisticalCostModel, ANodeCheaperToDrawThanToQueryIsDrawnWithoutOne) {
    const std::vector<Aabb> boxes = randomBoxes(1500, 3);
    const BspTree tree = buildTree(boxes);
    const std::vector<uint32_t> triangles(boxes.size(), 100);
    const CostModel costs{0.05, 1e-4, 0.0};  // one object: 0.01 ms; a query: 0.05 ms
    StatisticalCuller culler(paperWith([](StatisticalOptions& o) { o.cost_model = true; }), costs);
    culler.reset(tree);
    std::vector<uint8_t> visible(boxes.size(), 0);
    for (size_t i = 0; i < visible.size(); i += 3) visible[i] = 1;
    ScriptedQueryDevice device(4);
    const CullView view = makeView({0, 5, 0}, {0, 0, -100});
    for (uint64_t f = 0; f < 10; ++f) {
        CullFrame frame = makeFrame(view, f, f / 30.0);
        frame.object_triangles = triangles;
        const ScriptedFrame r = runScripted(culler, tree, device, boxes, visible, frame);
        expectConservative(r, boxes, visible, view, "frame " + std::to_string(f));
        if (f == 0) {
            EXPECT_GT(r.queries.size(), 0u) << "the nodes that pay are queried";
        }
        for (const QueryTag& t : r.queries) {
            ASSERT_EQ(t.subject, QueryTag::Subject::Node);
            EXPECT_GT(static_cast<double>(subtreeObjects(tree, t.index)) * 0.01, 0.05)
                << "node " << t.index << " is cheaper to draw than to query";
        }
    }
    // A query dearer than drawing the whole scene: no query at all, frustum culling.
    StatisticalCuller dear(paperWith([](StatisticalOptions& o) { o.cost_model = true; }),
                           CostModel{1e6, 1e-4, 0.0});
    dear.reset(tree);
    CullFrame frame = makeFrame(view, 0, 0.0);
    frame.object_triangles = triangles;
    const ScriptedFrame r = runScripted(dear, tree, device, boxes, visible, frame);
    EXPECT_TRUE(r.queries.empty());
    EXPECT_EQ(r.drawn.size(), inFrustum(boxes, view.frustum).size());
}

TEST(StatisticalCostModel, AQueryPaysWhenTheOcclusionRateTimesTheDrawCostExceedsItsCost) {
    const CostModel costs{0.02, 1e-4, 0.01};
    EXPECT_DOUBLE_EQ(costs.drawMs(1000), 0.11);
    EXPECT_TRUE(queryPays(costs, 0.11, 1, 0.5));    // saves 0.055 ms for 0.02 ms
    EXPECT_FALSE(queryPays(costs, 0.11, 1, 0.1));   // saves 0.011 ms for 0.02 ms
    EXPECT_FALSE(queryPays(costs, 0.11, 6, 1.0));   // six boxes cost 0.12 ms
    EXPECT_FALSE(queryPays(costs, 0.015, 1, 1.0));  // cheaper to draw than to query
}

// (3) Cost model, second rule: in a scene where nothing is ever occluded, the re-queries of
// visible nodes save nothing; the rate of such queries coming back occluded falls, and the
// culler stops paying for most of them (every 8th is still asked, to keep the rate measured).
// Where everything is hidden the queries pay, and none is dropped.
TEST(StatisticalCostModel, QueriesThatDoNotPayAreDroppedAndThoseThatPayAreKept) {
    const std::vector<Aabb> boxes = gridBoxes(16, 16);
    const BspTree tree = buildTree(boxes, 4, BspSplitRule::Sah);
    const std::vector<uint32_t> triangles(boxes.size(), 1000);
    const CostModel costs{0.05, 1e-4, 0.0};  // an object: 0.1 ms; a query: 0.05 ms
    const CullView view = overview(boxes);
    for (const bool occluded : {false, true}) {
        const std::vector<uint8_t> visible(boxes.size(), occluded ? 0 : 1);
        StatisticalOptions plain;
        plain.base_time_s = 0.1;  // re-query often, so that there is something to drop
        StatisticalOptions weighed = plain;
        weighed.cost_model = true;
        StatisticalCuller a(plain, costs), b(weighed, costs);
        a.reset(tree);
        b.reset(tree);
        ScriptedQueryDevice device(4);
        uint64_t queries_plain = 0, queries_weighed = 0;
        for (uint64_t f = 0; f < 120; ++f) {
            CullFrame frame = makeFrame(view, f, f / 30.0);
            frame.object_triangles = triangles;
            const ScriptedFrame ra = runScripted(a, tree, device, boxes, visible, frame);
            const ScriptedFrame rb = runScripted(b, tree, device, boxes, visible, frame);
            expectConservative(rb, boxes, visible, view, "frame " + std::to_string(f));
            if (f >= 60) {
                queries_plain += ra.queries.size();
                queries_weighed += rb.queries.size();
            }
        }
        if (occluded) {
            EXPECT_EQ(queries_weighed, queries_plain) << "hidden: every query pays";
        } else {
            EXPECT_LT(queries_weighed, queries_plain / 3) << "visible: re-queries do not pay";
            EXPECT_GT(queries_weighed, 0u) << "some are still asked";
            EXPECT_LT(b.occlusionEstimate(PriorResult::LastVisible).occluded, 0.05);
        }
    }
}

// (10) The frames a re-query's answer decides: the interval at this frame's rate (metres of
// travel per frame with the distance rules, seconds otherwise), between 1 and the frames before
// the statistics grow too old.
TEST(StatisticalRequeryHorizon, TheFramesAnAnswerDecidesAreTheIntervalAtThisFramesRate) {
    StatisticalOptions o;  // max_statistics_age_s = 2
    RequeryInterval seconds;
    seconds.interval = 0.5;
    EXPECT_DOUBLE_EQ(requeryHorizonFrames(o, seconds, 0.0, 0.1), 5.0);
    EXPECT_DOUBLE_EQ(requeryHorizonFrames(o, seconds, 0.0, 1.0), 1.0) << "at least one frame";
    EXPECT_DOUBLE_EQ(requeryHorizonFrames(o, seconds, 0.0, 0.0), 1.0) << "the first frame";
    EXPECT_DOUBLE_EQ(requeryHorizonFrames(o, seconds, 0.0, std::nan("")), 1.0);
    RequeryInterval metres;
    metres.distance = true;
    metres.interval = 3.0;
    EXPECT_DOUBLE_EQ(requeryHorizonFrames(o, metres, 0.5, 0.1), 6.0);
    EXPECT_DOUBLE_EQ(requeryHorizonFrames(o, metres, 0.001, 0.1), 20.0) << "2 s of 0.1 s frames";
    EXPECT_DOUBLE_EQ(requeryHorizonFrames(o, metres, 0.0, 0.1), 20.0) << "nothing moved";
}

// (10) A field of single-object leaves, each a little dearer to draw than to query, all visible.
// The cost model's estimate starts at even odds, so one frame's saving of a re-query (half the
// draw cost) is less than the query and the re-queries are put off; weighed over the 4.5 frames
// each answer decides, they pay and are issued. Either way nothing visible is left out.
TEST(StatisticalRequeryHorizon, AReQueryThatDecidesSeveralFramesPaysWhereOneFrameWouldNot) {
    const std::vector<Aabb> boxes = gridBoxes(8, 8);
    const BspTree tree = buildTree(boxes, 1, BspSplitRule::Sah);
    const std::vector<uint32_t> triangles(boxes.size(), 600);
    const CostModel costs{0.05, 1e-4, 0.0};  // an object: 0.06 ms; a query: 0.05 ms
    const CullView view = overview(boxes);
    const std::vector<uint8_t> visible(boxes.size(), 1);
    uint64_t leaf_requeries[2] = {0, 0};
    for (const bool horizon : {false, true}) {
        StatisticalOptions o;
        o.base_time_s = 0.1;  // one visible result: 0.15 s, 4.5 frames at 30 a second
        o.cost_model = true;
        o.draw_while_requerying = true;
        o.requery_horizon = horizon;
        StatisticalCuller culler(o, costs);
        culler.reset(tree);
        ScriptedQueryDevice device(4);
        for (uint64_t f = 0; f < 8; ++f) {
            CullFrame frame = makeFrame(view, f, f / 30.0);
            frame.object_triangles = triangles;
            const ScriptedFrame r = runScripted(culler, tree, device, boxes, visible, frame);
            expectConservative(r, boxes, visible, view, "frame " + std::to_string(f));
            if (f == 0) continue;  // the first queries, on fresh statistics
            for (const QueryTag& t : r.queries) {
                if (t.subject == QueryTag::Subject::Node && tree.node(t.index).isLeaf()) {
                    ++leaf_requeries[horizon];
                }
            }
        }
    }
    EXPECT_LT(leaf_requeries[0], 16u) << "over one frame: at most every 8th is asked anyway";
    EXPECT_GE(leaf_requeries[1], 48u) << "over the horizon: the re-queries pay";
}

// (4) Re-query by distance: CalcNodeAction's interval counted in metres travelled (the camera's
// and the node's movers'), or in travel relative to the node's distance (parallax).
TEST(CalcNodeAction, RequeryDistanceReplacesBaseTime) {
    StatisticalOptions o;
    o.requery_distance_m = 2.0;
    NodeStatistics s;
    recordQueryResult(o, s, true, 0.0, 10.0);  // travel counter 10 m at the query
    // One visible result: 2 m * 1.5 = 3 m of travel; time no longer counts (up to the age limit).
    EXPECT_EQ(decideNodeAction(o, s, false, 1.9, {12.9, 50.0}), NodeAction::Render);
    EXPECT_EQ(decideNodeAction(o, s, false, 0.1, {13.1, 50.0}), NodeAction::Query);
    EXPECT_EQ(decideNodeAction(o, s, false, 2.1, {10.0, 50.0}), NodeAction::Query) << "too old";
    o.requery_distance_m = 0.0;
    o.requery_parallax = 0.1;
    // 0.1 * 1.5 = 0.15 of the distance: 1.5 m at 10 m, 15 m at 100 m.
    EXPECT_EQ(decideNodeAction(o, s, false, 0.5, {11.6, 10.0}), NodeAction::Query);
    EXPECT_EQ(decideNodeAction(o, s, false, 0.5, {11.6, 100.0}), NodeAction::Render);
    EXPECT_EQ(decideNodeAction(o, s, false, 0.5, {25.1, 100.0}), NodeAction::Query);
}

// (4) A visible node is not re-queried while neither the camera nor anything in it moves, however
// long that lasts (within the age limit); it is re-queried once the camera has travelled the
// re-query distance, or once a mover inside it has.
TEST(StatisticalMotion, ReQueriesAfterTheCameraOrAMoverTravelledNotAfterSeconds) {
    const Aabb start{glm::vec3(-1, -1, -11), glm::vec3(1, 1, -9)};
    StatisticalOptions o;
    o.requery_distance_m = 1.0;    // 1.5 m after one visible result
    o.max_statistics_age_s = 100;  // out of the way
    StatisticalOptions seconds = o;
    seconds.requery_distance_m = 0.0;
    for (const bool by_distance : {true, false}) {
        std::vector<Aabb> boxes{start};
        BspTree tree = buildTree(boxes, 1);
        StatisticalCuller culler(by_distance ? o : seconds);
        culler.reset(tree);
        ScriptedQueryDevice device(0);
        const std::vector<uint8_t> visible{1};
        auto frame = [&](uint64_t f, glm::vec3 eye) {
            return runScripted(culler, tree, device, boxes, visible,
                               makeFrame(makeView(eye, eye + glm::vec3(0, 0, -10)), f, f / 30.0));
        };
        const glm::vec3 eye(0, 0, 0);
        EXPECT_EQ(frame(0, eye).queries.size(), 1u);
        uint64_t queries = 0;
        for (uint64_t f = 1; f < 150; ++f) queries += frame(f, eye).queries.size();  // 5 s, still
        if (!by_distance) {
            EXPECT_GT(queries, 0u) << "BASE_TIME re-queries a still scene";
            continue;
        }
        EXPECT_EQ(queries, 0u) << "nothing moved";
        EXPECT_EQ(frame(150, eye + glm::vec3(1.4f, 0, 0)).queries.size(), 0u);
        EXPECT_EQ(frame(151, eye + glm::vec3(1.6f, 0, 0)).queries.size(), 1u) << "camera moved";
        EXPECT_EQ(frame(152, eye + glm::vec3(1.6f, 0, 0)).queries.size(), 0u);
        // A mover: two visible results now, so 1 m * 1.75; the object travels 2 m in four steps
        // while the camera stands still.
        for (int step = 1; step <= 4; ++step) {
            boxes[0].min.x -= 0.5f;
            boxes[0].max.x -= 0.5f;
            tree.reinsert(0, boxes[0]);
            tree.refitDirtyBounds();
            const size_t q = frame(152 + step, eye + glm::vec3(1.6f, 0, 0)).queries.size();
            EXPECT_EQ(q, step == 4 ? 1u : 0u) << "mover step " << step;
        }
    }
}

// (5) Fallback: where nothing is occluded the culler stops querying and culls by the frustum
// only, looking again every fallback_recheck_s; where much is occluded it never falls back.
TEST(StatisticalFallback, NoOcclusionMeansFrustumCullingWithPeriodicRechecks) {
    const std::vector<Aabb> boxes = randomBoxes(1500, 3);
    const BspTree tree = buildTree(boxes);
    StatisticalOptions o;
    o.fallback = true;
    o.fallback_window_frames = 4;
    o.fallback_recheck_s = 0.5;
    o.base_time_s = 0.1;  // re-queries every few frames: answers to judge by
    const CullView view = makeView({0, 5, 0}, {0, 0, -100});
    const size_t in_frustum = inFrustum(boxes, view.frustum).size();
    for (const bool open : {true, false}) {
        std::vector<uint8_t> visible(boxes.size(), 1);
        if (!open) {
            for (size_t i = 0; i < visible.size(); i += 2) visible[i] = 0;
        }
        StatisticalCuller culler(o);
        culler.reset(tree);
        ScriptedQueryDevice device(4);
        std::vector<uint64_t> checking_frames;  // frames that ran the algorithm
        for (uint64_t f = 0; f < 90; ++f) {
            const ScriptedFrame r =
                runScripted(culler, tree, device, boxes, visible, makeFrame(view, f, f / 30.0));
            expectConservative(r, boxes, visible, view, "frame " + std::to_string(f));
            if (culler.lastFrame().frustum_only) {
                EXPECT_TRUE(r.queries.empty());
                EXPECT_EQ(r.drawn.size(), in_frustum) << "frustum culling";
            } else {
                checking_frames.push_back(f);
            }
        }
        if (!open) {
            EXPECT_EQ(checking_frames.size(), 90u) << "occlusion: never falls back";
            continue;
        }
        // Falls back after its window, then looks again every 0.5 s (15 frames) for a window.
        ASSERT_GE(checking_frames.size(), 8u);
        EXPECT_LT(checking_frames.size(), 45u);
        uint32_t rechecks = 0;
        for (size_t i = 1; i < checking_frames.size(); ++i) {
            if (checking_frames[i] != checking_frames[i - 1] + 1) {
                ++rechecks;
                EXPECT_GE(checking_frames[i] - checking_frames[i - 1], 15u);
            }
        }
        EXPECT_GE(rechecks, 3u);
    }
}

}  // namespace
}  // namespace occsim
