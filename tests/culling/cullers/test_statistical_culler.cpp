// The statistical culler (Kovalcik & Sochor 2005; culling/cullers/statistical_culler.h): its
// decision rule branch by branch, and whole traversals on the scripted query device and on test
// devices whose answers depend on what was drawn before them
// (occsim/culling/testing/depth_raster_device.h). No OpenGL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "culling/cullers/basic_cullers.h"
#include "culling/cullers/statistical_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/testing/depth_raster_device.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

using testing::buildTree;
using testing::Camera;
using testing::inFrustum;
using testing::makeCamera;
using testing::makeFrame;
using testing::makeView;
using testing::randomBoxes;

// A wall of boxes across the view near the camera, and a field of small boxes behind it that the
// wall hides completely.
struct WallAndField {
    std::vector<Aabb> boxes;
    uint32_t wall_count = 0;
    WallAndField() {
        for (int i = 0; i < 16; ++i) {
            const float x = -24.0f + 3.0f * static_cast<float>(i);
            boxes.push_back({glm::vec3(x, 0, -1), glm::vec3(x + 2.9f, 12, 0)});
        }
        wall_count = static_cast<uint32_t>(boxes.size());
        for (int z = 0; z < 24; ++z) {
            for (int x = 0; x < 16; ++x) {
                const glm::vec3 lo(-24.0f + 3.0f * static_cast<float>(x), 0.0f,
                                   -8.0f - 4.0f * static_cast<float>(z));
                boxes.push_back({lo, lo + glm::vec3(1.0f, 1.5f, 1.0f)});
            }
        }
    }
};

// What a culler did over one frame on the depth raster: objects drawn that ground truth does not
// see, and objects ground truth sees that were not drawn.
struct DepthFrame {
    uint64_t hidden_drawn = 0;
    uint64_t hidden_in_frustum = 0;  // what frustum culling alone would draw in vain
    uint64_t missed = 0;
};

DepthFrame runDepthFrame(Culler& culler, const BspTree& tree, DepthRasterDevice& device,
                         const std::vector<Aabb>& boxes, const Camera& cam, uint64_t frame) {
    device.beginFrame(cam.view_projection, cam.view.eye, boxes);
    culler.cullAndRender(tree, makeFrame(cam.view, frame, static_cast<double>(frame) / 30.0),
                         device);
    const std::vector<uint8_t> truth = device.groundTruth();
    DepthFrame out;
    std::vector<uint8_t> drawn(boxes.size(), 0);
    for (uint32_t o : device.drawnObjects()) {
        drawn[o] = 1;
        out.hidden_drawn += !truth[o];
    }
    for (uint32_t o = 0; o < boxes.size(); ++o) {
        out.missed += truth[o] && !drawn[o];
        out.hidden_in_frustum +=
            !truth[o] && classify(cam.view.frustum, boxes[o]) != FrustumTest::Outside;
    }
    return out;
}

// The paper's queue is processed front to back: the children of the nodes whose answers come back
// in one pass go back to the queue start in the order of their parents, nearest first (Kovalcik
// & Sochor 2005, section 3, "queue.AddChildrenBeforePointer"). Then the wall in front is drawn
// before the field behind it is queried, and the field is culled. Taken in the reverse order,
// the farthest subtree is traversed first and most of the field is drawn before the wall.
TEST(StatisticalPaperOrder, AWallDrawnFirstHidesTheFieldBehindIt) {
    const WallAndField scene;
    const BspTree tree = buildTree(scene.boxes, 4, BspSplitRule::Sah);
    StatisticalCuller culler;  // the paper's options
    culler.reset(tree);
    DepthRasterDevice device(64, 48, 8);
    DepthFrame total;
    for (uint64_t f = 0; f < 60; ++f) {
        const Camera cam = makeCamera({0.2f * static_cast<float>(f) - 6.0f, 3, 12}, {0, 2, -40});
        const DepthFrame d = runDepthFrame(culler, tree, device, scene.boxes, cam, f);
        EXPECT_EQ(d.missed, 0u) << "frame " << f;
        ASSERT_GT(d.hidden_in_frustum, 100u) << "the field behind the wall is in view";
        if (f == 0) {
            EXPECT_LT(d.hidden_drawn, d.hidden_in_frustum / 10) << "first frame";
        }
        total.hidden_drawn += d.hidden_drawn;
        total.hidden_in_frustum += d.hidden_in_frustum;
    }
    EXPECT_LT(total.hidden_drawn, total.hidden_in_frustum / 10);
}

// The same order, read from the queries themselves: with every answer visible and late, each
// pass queries one level of the tree, and each level in front-to-back order of the tree (the
// nearer child's subtree before the farther one's).
TEST(StatisticalPaperOrder, EachPassQueriesTheNextLevelFrontToBack) {
    const std::vector<Aabb> boxes = testing::randomBoxes(300, 9);
    const BspTree tree = buildTree(boxes, 2);
    Aabb all;
    for (const Aabb& b : boxes) extend(all, b);
    const CullView view = testing::makeView(center(all) + glm::vec3(30, 250, 220), center(all));
    ASSERT_EQ(testing::inFrustum(boxes, view.frustum).size(), boxes.size());

    // Front-to-back depth-first order of the non-empty nodes, then stably by depth.
    std::vector<uint32_t> expected;
    std::vector<uint32_t> stack = {tree.root()};
    while (!stack.empty()) {
        const uint32_t n = stack.back();
        stack.pop_back();
        if (isEmpty(tree.bounds(n))) continue;
        expected.push_back(n);
        const BspNode& node = tree.node(n);
        if (node.isLeaf()) continue;
        const bool eye_below = view.eye[node.axis] < node.split;
        stack.push_back(node.child[eye_below ? 1 : 0]);
        stack.push_back(node.child[eye_below ? 0 : 1]);
    }
    std::stable_sort(expected.begin(), expected.end(), [&](uint32_t a, uint32_t b) {
        return tree.node(a).depth < tree.node(b).depth;
    });

    StatisticalOptions o;
    o.queries_before_restart = 100000;  // one pass per level
    StatisticalCuller culler(o);
    culler.reset(tree);
    ScriptedQueryDevice device(1000000);  // no answer is ready before the pass ends
    device.setVisibility(std::vector<uint8_t>(boxes.size(), 1), boxes);
    culler.cullAndRender(tree, makeFrame(view, 0, 0.0), device);
    std::vector<uint32_t> queried;
    for (const QueryTag& t : device.queryTags()) queried.push_back(t.index);
    EXPECT_EQ(queried, expected);
}

// --- Every configuration stays conservative, and deterministic --------------------------------

class StatisticalConservative : public ::testing::TestWithParam<std::string> {};

StatisticalOptions optionsNamed(const std::string& name) {
    StatisticalOptions o;
    if (name == "paper") return o;
    if (name == "plus") return StatisticalOptions::plus();
    if (name == "ready") o.ready_answers = true;
    if (name == "leaves") o.virtual_leaves = true;
    if (name == "objects") o.object_queries = true;
    if (name == "costs") o.cost_model = true;
    if (name == "distance") o.requery_distance_m = 2.0;
    if (name == "parallax") o.requery_parallax = 0.1;
    if (name == "fallback") o.fallback = true;
    if (name == "draw") {
        o.ready_answers = true;
        o.draw_while_requerying = true;
    }
    if (name == "weigh") {
        o.ready_answers = true;
        o.weigh_in_flight = true;
    }
    if (name == "descend") {
        o.ready_answers = true;
        o.descend_visible_inner_nodes = true;
        o.draw_while_requerying = true;
    }
    if (name == "waits") {
        o.ready_answers = true;
        o.weigh_in_flight = true;
        o.waits_per_frame = 2;
    }
    if (name == "horizon") {
        o.cost_model = true;
        o.draw_while_requerying = true;
        o.requery_horizon = true;
    }
    if (name == "nearest") {
        o.virtual_leaves = true;
        o.distance_order = true;
    }
    return o;
}

// On the depth raster (nearer drawn boxes hide farther ones), with a moving camera, movers and
// straddlers, every object ground truth sees is drawn in every frame, whatever the options;
// and the same run twice makes the same decisions.
TEST_P(StatisticalConservative, DrawsEverythingGroundTruthSeesAndDecidesTheSameTwice) {
    WallAndField scene;
    // Bars across the field (straddlers) and a few movers among the field's boxes.
    for (int i = 0; i < 4; ++i) {
        const float z = -20.0f - 18.0f * static_cast<float>(i);
        scene.boxes.push_back({glm::vec3(-24, 0, z), glm::vec3(24, 0.8f, z + 0.6f)});
    }
    const std::vector<uint32_t> triangles(scene.boxes.size(), 500);
    std::vector<std::vector<uint32_t>> first_run;
    for (int run = 0; run < 2; ++run) {
        std::vector<Aabb> boxes = scene.boxes;
        BspTree tree = buildTree(boxes, 4, BspSplitRule::Sah);
        StatisticalCuller culler(optionsNamed(GetParam()), CostModel{0.01, 1e-4, 0.002});
        culler.reset(tree);
        DepthRasterDevice device(64, 48, 6);
        for (uint64_t f = 0; f < 90; ++f) {
            for (uint32_t m = scene.wall_count; m < scene.wall_count + 40; m += 4) {
                const float dx = 0.15f * std::sin(0.2f * static_cast<float>(f + m));
                boxes[m].min.x += dx;
                boxes[m].max.x += dx;
                tree.reinsert(m, boxes[m]);
            }
            tree.refitDirtyBounds();
            const float t = static_cast<float>(f);
            // Walks towards the wall, then rises over it and looks down on the field.
            const glm::vec3 eye = f < 45 ? glm::vec3(0.3f * t - 6.0f, 3, 20 - 0.2f * t)
                                         : glm::vec3(7.0f, 3.0f + 0.5f * (t - 45), 11);
            const Camera cam = makeCamera(eye, {0, 0, -50});
            device.beginFrame(cam.view_projection, cam.view.eye, boxes);
            CullFrame frame = makeFrame(cam.view, f, f / 30.0);
            frame.object_triangles = triangles;
            culler.cullAndRender(tree, frame, device);
            const std::vector<uint8_t> truth = device.groundTruth();
            std::vector<uint8_t> drawn(boxes.size(), 0);
            for (uint32_t o : device.drawnObjects()) {
                EXPECT_FALSE(drawn[o]) << "object " << o << " drawn twice, frame " << f;
                drawn[o] = 1;
            }
            for (uint32_t o = 0; o < boxes.size(); ++o) {
                EXPECT_FALSE(truth[o] && !drawn[o]) << "object " << o << " missed, frame " << f;
            }
            // Only this frame's draw-while-requerying answers may still be in flight: every
            // answer a decision waits on is taken within its frame, the others in the next.
            EXPECT_LE(device.pendingQueries(), culler.lastFrame().update_queries);
            if (run == 0) {
                first_run.push_back(device.drawnObjects());
            } else {
                EXPECT_EQ(device.drawnObjects(), first_run[f]) << "frame " << f;
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Options, StatisticalConservative,
                         ::testing::Values("paper", "ready", "leaves", "objects", "costs",
                                           "distance", "parallax", "fallback", "draw", "weigh",
                                           "descend", "waits", "horizon", "nearest", "plus"));

StatisticalOptions paperOptions() { return StatisticalOptions{}; }

// (11) A wall too wide for either child of the root's split stays in the root (a virtual leaf),
// and a field of boxes behind it fills both children. In the tree's depth-first order the root's
// virtual leaf comes after its nearer child, so the nearer half of the field is queried before
// the wall is drawn, comes back visible and is drawn while hidden until its re-query; nearest
// first, the wall (the root's bounds hold the eye: distance 0) is drawn before anything behind it
// is queried.
TEST(StatisticalDistanceOrder, AWallStoredInAnInnerNodeIsDrawnBeforeTheFieldItHides) {
    std::vector<Aabb> boxes = {{glm::vec3(-30, 0, -1), glm::vec3(30, 12, 0)}};  // the wall
    for (int z = 0; z < 12; ++z) {
        for (int x = 0; x < 16; ++x) {
            const glm::vec3 lo(-24.0f + 3.0f * static_cast<float>(x), 0.0f,
                               -6.0f - 3.0f * static_cast<float>(z));
            boxes.push_back({lo, lo + glm::vec3(1.0f, 1.5f, 1.0f)});
        }
    }
    boxes.push_back({glm::vec3(-30, 0, 14), glm::vec3(30, 0.1f, 15)});  // the eye inside the root
    const BspTree tree = buildTree(boxes, 4, BspSplitRule::Sah);
    ASSERT_NE(tree.firstObject(tree.root()), BspTree::kNone)
        << "the wall straddles the root's split";
    uint64_t hidden_drawn[2] = {0, 0};
    for (const bool nearest : {false, true}) {
        StatisticalOptions o;
        o.virtual_leaves = true;
        o.distance_order = nearest;
        StatisticalCuller culler(o);
        culler.reset(tree);
        DepthRasterDevice device(64, 48, 8);
        for (uint64_t f = 0; f < 30; ++f) {
            const Camera cam =
                makeCamera({-6.0f + 0.1f * static_cast<float>(f), 3, 12}, {0, 2, -40});
            const DepthFrame d = runDepthFrame(culler, tree, device, boxes, cam, f);
            EXPECT_EQ(d.missed, 0u) << "frame " << f;
            ASSERT_GT(d.hidden_in_frustum, 100u) << "the field behind the wall is in view";
            if (f > 0) hidden_drawn[nearest] += d.hidden_drawn;  // frame 0: everything fresh
        }
    }
    EXPECT_LT(hidden_drawn[1] * 4, hidden_drawn[0])
        << "hidden boxes drawn over frames 1 to 29, in the tree's order " << hidden_drawn[0]
        << ", nearest first " << hidden_drawn[1];
}

TEST(CalcNodeAction, RendersWithoutQueryWhenTheNearPlaneMayCutTheBox) {
    NodeStatistics stats;  // even with no statistics at all
    EXPECT_EQ(decideNodeAction(paperOptions(), stats, true, 5.0), NodeAction::Render);
}

TEST(CalcNodeAction, QueriesANodeWithoutStatistics) {
    EXPECT_EQ(decideNodeAction(paperOptions(), NodeStatistics{}, false, 0.0), NodeAction::Query);
}

TEST(CalcNodeAction, QueriesWhenStatisticsAreTooOld) {
    StatisticalOptions o = paperOptions();
    o.max_statistics_age_s = 0.5;
    NodeStatistics s;
    recordQueryResult(o, s, true, 10.0);
    EXPECT_EQ(decideNodeAction(o, s, false, 10.4), NodeAction::Render);
    EXPECT_EQ(decideNodeAction(o, s, false, 10.6), NodeAction::Query);
}

TEST(CalcNodeAction, QueriesWhenTheLastResultWasOccluded) {
    NodeStatistics s;
    recordQueryResult(paperOptions(), s, true, 0.0);
    recordQueryResult(paperOptions(), s, true, 0.1);
    recordQueryResult(paperOptions(), s, false, 0.2);
    EXPECT_EQ(decideNodeAction(paperOptions(), s, false, 0.2), NodeAction::Query);
}

TEST(CalcNodeAction, RendersUntilBaseTimeTimesDecayThenQueries) {
    // BASE_TIME = 2/3 s, a = 2, b = 0.5: one visible result -> 2/3 * 1.5 = 1.0 s;
    // two -> 2/3 * 1.75 = 1.1667 s; three -> 2/3 * 1.875 = 1.25 s.
    const StatisticalOptions o = paperOptions();
    const double expected[] = {1.0, 7.0 / 6.0, 1.25};
    NodeStatistics s;
    for (int n = 0; n < 3; ++n) {
        recordQueryResult(o, s, true, 0.0);
        EXPECT_EQ(decideNodeAction(o, s, false, expected[n] - 1e-6), NodeAction::Render) << n;
        EXPECT_EQ(decideNodeAction(o, s, false, expected[n] + 1e-6), NodeAction::Query) << n;
    }
}

TEST(CalcNodeAction, DecayCurveAndHistoryLengthAreParameters) {
    StatisticalOptions o = paperOptions();
    o.base_time_s = 1.0;
    o.decay_a = 3.0;
    o.decay_b = 0.25;
    o.history_length = 2;
    o.max_statistics_age_s = 10.0;
    NodeStatistics s;
    for (int i = 0; i < 5; ++i) recordQueryResult(o, s, true, 0.0);
    // Only the last 2 results count: occ_num = 2 -> 1.0 * (3 - 0.0625) = 2.9375 s.
    EXPECT_EQ(decideNodeAction(o, s, false, 2.93), NodeAction::Render);
    EXPECT_EQ(decideNodeAction(o, s, false, 2.94), NodeAction::Query);
}

struct OneObjectWorld {
    std::vector<Aabb> boxes{{glm::vec3(-1, -1, -11), glm::vec3(1, 1, -9)}};
    BspTree tree = buildTree(boxes);
    ScriptedQueryDevice device{0};
    StatisticalCuller culler;
    OneObjectWorld() { culler.reset(tree); }

    void frame(const CullView& view, double t, bool visible) {
        device.setVisibility({static_cast<uint8_t>(visible)}, boxes);
        device.clearLog();
        device.resetCounters();
        culler.cullAndRender(tree, makeFrame(view, 0, t), device);
    }
};

TEST(StatisticalCuller, SkipsAFrustumCulledNodeWithoutQueryOrDraw) {
    OneObjectWorld w;
    w.frame(makeView({0, 0, 0}, {0, 0, 10}), 0.0, true);  // looking away
    EXPECT_EQ(w.device.counters().queries_issued, 0u);
    EXPECT_TRUE(w.device.drawnObjects().empty());
}

TEST(StatisticalCuller, RendersWithoutQueryWhenTheViewerIsInsideTheBox) {
    OneObjectWorld w;
    w.frame(makeView({0, 0, -10}, {0, 0, -20}), 0.0, false);
    EXPECT_EQ(w.device.counters().queries_issued, 0u);
    EXPECT_EQ(w.device.drawnObjects(), std::vector<uint32_t>{0});
}

TEST(StatisticalCuller, QueriesFirstThenTrustsVisibleStatisticsThenQueriesAgain) {
    OneObjectWorld w;
    const CullView view = makeView({0, 0, 0}, {0, 0, -10});
    w.frame(view, 0.0, true);  // no statistics: query, visible, drawn
    EXPECT_EQ(w.device.counters().queries_issued, 1u);
    EXPECT_EQ(w.device.drawnObjects(), std::vector<uint32_t>{0});
    w.frame(view, 0.5, true);  // within BASE_TIME * 1.5: drawn with no query
    EXPECT_EQ(w.device.counters().queries_issued, 0u);
    EXPECT_EQ(w.device.drawnObjects(), std::vector<uint32_t>{0});
    w.frame(view, 1.05, true);  // past it: query again
    EXPECT_EQ(w.device.counters().queries_issued, 1u);
    EXPECT_EQ(w.device.drawnObjects(), std::vector<uint32_t>{0});
}

TEST(StatisticalCuller, QueriesAnOccludedNodeEveryFrameAndNeverDrawsIt) {
    OneObjectWorld w;
    const CullView view = makeView({0, 0, 0}, {0, 0, -10});
    for (int f = 0; f < 5; ++f) {
        w.frame(view, f * 0.1, false);
        EXPECT_EQ(w.device.counters().queries_issued, 1u) << f;
        EXPECT_TRUE(w.device.drawnObjects().empty()) << f;
    }
    w.frame(view, 0.6, true);  // it appears: the query of this very frame finds it
    EXPECT_EQ(w.device.drawnObjects(), std::vector<uint32_t>{0});
}

TEST(StatisticalCuller, QueriesAgainWhenStatisticsAreTooOld) {
    OneObjectWorld w;
    StatisticalOptions o;
    o.max_statistics_age_s = 0.2;
    w.culler = StatisticalCuller(o);
    w.culler.reset(w.tree);
    const CullView view = makeView({0, 0, 0}, {0, 0, -10});
    w.frame(view, 0.0, true);
    w.frame(view, 0.1, true);
    EXPECT_EQ(w.device.counters().queries_issued, 0u);
    w.frame(view, 0.35, true);
    EXPECT_EQ(w.device.counters().queries_issued, 1u);
}

class TwoQueueTraversal : public ::testing::TestWithParam<uint32_t> {};

// Over frames with visibility changing at random and any query latency, the statistical culler
// draws every visible object in the frustum, draws nothing outside it, and draws nothing twice.
TEST_P(TwoQueueTraversal, DrawsEveryObjectTheScriptedVisibilitySaysIsVisible) {
    const uint32_t latency = GetParam();
    const std::vector<Aabb> boxes = randomBoxes(1500, 7);
    const BspTree tree = buildTree(boxes);
    ScriptedQueryDevice device(latency);
    StatisticalCuller culler;
    culler.reset(tree);
    std::mt19937 rng(11);
    std::bernoulli_distribution visible_draw(0.15);
    uint64_t total_queries = 0;
    for (uint32_t f = 0; f < 60; ++f) {
        const float a = 0.05f * static_cast<float>(f);
        const CullView view = makeView({0, 5, 0}, {100 * std::cos(a), 0, 100 * std::sin(a)});
        std::vector<uint8_t> visible(boxes.size());
        for (auto& v : visible) v = visible_draw(rng);
        device.setVisibility(visible, boxes);
        device.clearLog();
        device.resetCounters();
        culler.cullAndRender(tree, makeFrame(view, f, f / 30.0), device);
        total_queries += device.counters().queries_issued;

        const std::set<uint32_t> frustum = inFrustum(boxes, view.frustum);
        std::set<uint32_t> drawn;
        for (uint32_t o : device.drawnObjects()) {
            EXPECT_TRUE(drawn.insert(o).second) << "object " << o << " drawn twice in frame " << f;
            EXPECT_TRUE(frustum.count(o)) << "object " << o << " drawn outside the frustum";
        }
        for (uint32_t o : frustum) {
            if (visible[o]) {
                EXPECT_TRUE(drawn.count(o)) << "visible object " << o << " missed in frame " << f;
            }
        }
        EXPECT_EQ(device.pendingQueries(), 0u) << "every query is answered within its frame";
    }
    EXPECT_GT(total_queries, 0u);
}

INSTANTIATE_TEST_SUITE_P(Latencies, TwoQueueTraversal, ::testing::Values(0u, 3u, 40u, 1000u));

TEST(StatisticalCuller, IssuesFewerQueriesThanStopAndWaitOnACoherentScene) {
    const std::vector<Aabb> boxes = randomBoxes(1500, 3);
    const BspTree tree = buildTree(boxes);
    std::vector<uint8_t> visible(boxes.size());
    for (size_t i = 0; i < visible.size(); i += 3) visible[i] = 1;
    ScriptedQueryDevice stat_device(4), saw_device(4);
    stat_device.setVisibility(visible, boxes);
    saw_device.setVisibility(visible, boxes);
    StatisticalCuller statistical;
    StopAndWaitCuller stop_and_wait;
    statistical.reset(tree);
    const CullView view = makeView({0, 5, 0}, {0, 0, -100});
    for (int f = 0; f < 20; ++f) {
        statistical.cullAndRender(tree, makeFrame(view, f, f / 30.0), stat_device);
        stop_and_wait.cullAndRender(tree, makeFrame(view, f, f / 30.0), saw_device);
    }
    EXPECT_LT(stat_device.counters().queries_issued, saw_device.counters().queries_issued / 2);
    EXPECT_EQ(saw_device.counters().results_waited, saw_device.counters().queries_issued)
        << "stop-and-wait blocks on every query";
}

TEST(StatisticalCuller, ReturnsToTheQueueStartAfterTheConfiguredNumberOfQueries) {
    // With a latency longer than any frame, answers are never ready in the main loop: the loop
    // must stop after queries_before_restart queries and collect their answers before going on.
    const std::vector<Aabb> boxes = randomBoxes(800, 5);
    const BspTree tree = buildTree(boxes, 1);
    StatisticalOptions o;
    o.queries_before_restart = 5;
    StatisticalCuller culler(o);
    culler.reset(tree);
    ScriptedQueryDevice device(1000000);
    device.setVisibility(std::vector<uint8_t>(boxes.size(), 1), boxes);
    culler.cullAndRender(tree, makeFrame(makeView({0, 5, 0}, {0, 0, -100}), 0, 0.0), device);
    EXPECT_GT(device.counters().queries_issued, 5u);
    EXPECT_LE(device.maxPendingQueries(), 5u);
    EXPECT_EQ(device.counters().results_waited, device.counters().queries_issued);
}

// A wrapper that forwards queries but keeps counters of its own (all zero): a culler that looked
// at the device's counters to learn whether it blocked would never see a wait through it.
class OwnCountersDevice final : public RenderDevice {
  public:
    explicit OwnCountersDevice(RenderDevice& inner) : inner_(inner) {}
    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override { inner_.drawObject(object); }
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> tags) override {
        return inner_.issueQuery(boxes, tags);
    }
    bool isQueryReady(QueryId id) override { return inner_.isQueryReady(id); }
    QueryAnswer takeAnswer(QueryId id) override { return inner_.takeAnswer(id); }

  private:
    RenderDevice& inner_;
};

TEST(StatisticalCuller, CountsTheAnswersItBlockedOnFromTheAnswersThemselves) {
    const std::vector<Aabb> boxes = randomBoxes(800, 5);
    const BspTree tree = buildTree(boxes, 1);
    StatisticalCuller culler;
    culler.reset(tree);
    ScriptedQueryDevice scripted(1000000);  // never ready: every answer is waited for
    scripted.setVisibility(std::vector<uint8_t>(boxes.size(), 1), boxes);
    OwnCountersDevice device(scripted);
    culler.cullAndRender(tree, makeFrame(makeView({0, 5, 0}, {0, 0, -100}), 0, 0.0), device);
    ASSERT_GT(scripted.counters().results_waited, 0u);
    EXPECT_EQ(device.counters().results_waited, 0u) << "the wrapper's own counters";
    EXPECT_EQ(culler.lastFrame().blocked_answers, scripted.counters().results_waited);
}

}  // namespace
}  // namespace occsim
