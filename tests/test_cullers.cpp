// Culling logic on the scripted query device: no OpenGL involved.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "culling/cullers/basic_cullers.h"
#include "culling/cullers/statistical_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/devices/approximate_device.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/depth_raster_device.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

using testing::makeFrame;
using testing::makeView;
using testing::randomBoxes;

using testing::buildTree;
using testing::inFrustum;

// --- CalcNodeAction, branch by branch --------------------------------------------------------

StatisticalOptions paperOptions() { return StatisticalOptions{}; }

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

TEST(StatisticalOptions, TheDescriptorRejectsOutOfRangeValuesWithAMessageNamingTheKey) {
    for (const char* name : {"statistical", "statistical+"}) {
        const AlgorithmTraits& a = *findAlgorithm(name);
        EXPECT_EQ(checkOptionValues(a, OptionValues(a.options)), "") << name;
        const auto rejected = [&](const char* key, double value) {
            OptionValues v(a.options);
            v.set(key, value);
            return checkOptionValues(a, v);
        };
        EXPECT_EQ(rejected("decay_b", 1.5), "decay_b: expected a number in [0, 1], got 1.5");
        EXPECT_EQ(rejected("history_length", 0).rfind("history_length: ", 0), 0u);
        EXPECT_EQ(rejected("base_time", std::nan("")).rfind("base_time: ", 0), 0u);
        EXPECT_EQ(rejected("ready_answers", 2).rfind("ready_answers: expected true or false", 0),
                  0u);
    }
    // The rule tying two options together is the culler's own (its validate hook).
    const AlgorithmTraits& plus = *findAlgorithm("statistical+");
    OptionValues both(plus.options);
    both.set("requery_distance", 3.0);
    EXPECT_NE(checkOptionValues(plus, both).find("alternatives"), std::string::npos);
    // A sweep or the tuner sets one alternative and switches the other off.
    both.setWithAlternatives("requery_distance", 3.0);
    EXPECT_EQ(both.number("requery_parallax"), 0.0);
    EXPECT_EQ(checkOptionValues(plus, both), "");
    // The values a culler reads are the descriptor's defaults: the paper's, or every improvement.
    EXPECT_EQ(statisticalOptionTable()
                  .read(OptionValues(findAlgorithm("statistical")->options))
                  .base_time_s,
              StatisticalOptions::paper().base_time_s);
    EXPECT_TRUE(statisticalOptionTable().read(OptionValues(plus.options)).fallback);
}

// --- The statistical culler's branches, through the scripted device ---------------------------

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

// --- Whole traversals against the scripted visibility ------------------------------------------

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

// --- VFC, stop-and-wait, ideal ------------------------------------------------------------------

TEST(VfcCuller, DrawsExactlyTheObjectsABruteForceFrustumTestKeeps) {
    const std::vector<Aabb> boxes = randomBoxes(3000, 21);
    const BspTree tree = buildTree(boxes);
    VfcCuller vfc;
    ScriptedQueryDevice device;
    device.setVisibility(std::vector<uint8_t>(boxes.size(), 0), boxes);
    for (int i = 0; i < 12; ++i) {
        const float a = 0.5f * static_cast<float>(i);
        const CullView view =
            makeView({10 * std::sin(a), 3, 10 * std::cos(a)},
                     {100 * std::cos(a), -5, 100 * std::sin(a)}, 50.0f, 0.5f, 80.0f);
        device.clearLog();
        vfc.cullAndRender(tree, makeFrame(view, 0, 0.0), device);
        std::vector<uint32_t> drawn = device.drawnObjects();
        std::sort(drawn.begin(), drawn.end());
        const std::set<uint32_t> expected = inFrustum(boxes, view.frustum);
        EXPECT_EQ(drawn, std::vector<uint32_t>(expected.begin(), expected.end())) << "view " << i;
        EXPECT_EQ(device.counters().queries_issued, 0u);
    }
}

TEST(StopAndWaitCuller, DrawsExactlyTheVisibleObjectsInTheFrustum) {
    const std::vector<Aabb> boxes = randomBoxes(1000, 9);
    const BspTree tree = buildTree(boxes);
    std::vector<uint8_t> visible(boxes.size());
    for (size_t i = 0; i < visible.size(); i += 4) visible[i] = 1;
    ScriptedQueryDevice device(2);
    device.setVisibility(visible, boxes);
    StopAndWaitCuller culler;
    const CullView view = makeView({0, 5, 0}, {0, 0, -100});
    culler.cullAndRender(tree, makeFrame(view, 0, 0.0), device);
    const std::set<uint32_t> drawn(device.drawnObjects().begin(), device.drawnObjects().end());
    for (uint32_t o : inFrustum(boxes, view.frustum)) {
        if (visible[o]) {
            EXPECT_TRUE(drawn.count(o)) << o;
        }
    }
    EXPECT_LT(drawn.size(), inFrustum(boxes, view.frustum).size());
}

TEST(IdealCuller, DrawsOnlyGroundTruthVisibleObjectsAndIssuesNoQueries) {
    const std::vector<Aabb> boxes = randomBoxes(500, 4);
    const BspTree tree = buildTree(boxes);
    std::vector<uint8_t> truth(boxes.size());
    const CullView view = makeView({0, 5, 0}, {0, 0, -100});
    const std::set<uint32_t> frustum = inFrustum(boxes, view.frustum);
    for (uint32_t o : frustum) truth[o] = o % 2;
    CullFrame frame = makeFrame(view, 0, 0.0);
    frame.ground_truth_visible = truth;
    ScriptedQueryDevice device;
    device.setVisibility(std::vector<uint8_t>(boxes.size(), 0), boxes);
    IdealCuller ideal;
    EXPECT_TRUE(findAlgorithm(ideal.name())->oracle) << "the registry says it needs ground truth";
    ideal.cullAndRender(tree, frame, device);
    std::vector<uint32_t> drawn = device.drawnObjects();
    std::sort(drawn.begin(), drawn.end());
    std::vector<uint32_t> expected;
    for (uint32_t o = 0; o < truth.size(); ++o) {
        if (truth[o]) expected.push_back(o);
    }
    EXPECT_EQ(drawn, expected);
    EXPECT_EQ(device.counters().queries_issued, 0u);
}

}  // namespace
}  // namespace occsim

namespace occsim {
namespace {

// --- Approximate visibility for any culler ------------------------------------------------------

struct TwoObjects {
    std::vector<Aabb> boxes{{glm::vec3(0), glm::vec3(1)}, {glm::vec3(5), glm::vec3(6)}};
    Aabb both{glm::vec3(0), glm::vec3(6)};
};

TEST(ApproximateDevice, ThresholdTurnsSmallSampleCountsIntoOccluded) {
    TwoObjects w;
    ScriptedQueryDevice scripted(0);
    scripted.setVisibility({1, 1}, w.boxes);  // the scripted "samples" are visible objects hit
    ApproximateDevice device(scripted, {2, false});
    const QueryAnswer one = device.takeAnswer(device.issueQuery(w.boxes[0]));
    EXPECT_FALSE(one.visible) << "1 sample <= 2";
    EXPECT_EQ(one.samples, 1u) << "the samples are reported as they were";
    EXPECT_FALSE(device.takeAnswer(device.issueQuery(w.both)).visible) << "2 samples <= 2";
    ApproximateDevice exact(scripted, {0, false});
    const QueryAnswer seen = exact.takeAnswer(exact.issueQuery(w.boxes[0]));
    EXPECT_TRUE(seen.visible);
    EXPECT_EQ(seen.samples, 1u);
}

TEST(ApproximateDevice, StaleResultsAnswerAtOnceWithTheLastResultForTheSameBoxes) {
    TwoObjects w;
    ScriptedQueryDevice scripted(100);  // results take 100 commands
    ApproximateDevice device(scripted, {0, true});
    scripted.setVisibility({1, 0}, w.boxes);
    // No previous result: it waits, like any device.
    const QueryAnswer first = device.takeAnswer(device.issueQuery(w.boxes[0]));
    EXPECT_TRUE(first.visible);
    EXPECT_TRUE(first.waited);
    EXPECT_EQ(scripted.counters().results_waited, 1u);
    // The object disappears; the next query is not ready and gets last frame's answer at once.
    scripted.setVisibility({0, 0}, w.boxes);
    const QueryId q = device.issueQuery(w.boxes[0]);
    EXPECT_TRUE(device.isQueryReady(q));
    const QueryAnswer stale = device.takeAnswer(q);
    EXPECT_TRUE(stale.visible) << "stale: still visible";
    EXPECT_FALSE(stale.waited) << "a stale answer is not waited for";
    EXPECT_EQ(device.staleAnswers(), 1u);
    EXPECT_EQ(scripted.counters().results_waited, 1u) << "no new wait";
    EXPECT_EQ(device.lateResultsPending(), 1u);
    // Once the real result arrives it becomes the answer for next time.
    for (int i = 0; i < 120; ++i) scripted.drawObject(1);
    const QueryId again = device.issueQuery(w.boxes[0]);
    EXPECT_EQ(device.lateResultsPending(), 0u);
    EXPECT_FALSE(device.takeAnswer(again).visible)
        << "the late result (occluded) is now the last one";
}

TEST(ApproximateDevice, MakesTheStatisticalCullerMissObjectsOnlyWhenActive) {
    const std::vector<Aabb> boxes = testing::randomBoxes(600, 13);
    BspTree tree = buildTree(boxes);
    std::vector<uint8_t> visible(boxes.size());
    for (size_t i = 0; i < visible.size(); i += 2) visible[i] = 1;
    const CullView view = makeView({0, 5, 0}, {0, 0, -100});
    for (uint32_t threshold : {0u, 3u}) {
        ScriptedQueryDevice scripted(4);
        scripted.setVisibility(visible, boxes);
        ApproximateDevice device(scripted, {threshold, false});
        StatisticalCuller culler;
        culler.reset(tree);
        culler.cullAndRender(tree, makeFrame(view, 0, 0.0), device);
        const std::set<uint32_t> drawn(scripted.drawnObjects().begin(),
                                       scripted.drawnObjects().end());
        size_t missed = 0;
        for (uint32_t o : inFrustum(boxes, view.frustum)) missed += visible[o] && !drawn.count(o);
        if (threshold == 0) {
            EXPECT_EQ(missed, 0u);
        } else {
            EXPECT_GT(missed, 0u) << "a threshold of 3 hides nodes with few visible objects";
        }
    }
}

// --- Query answers: one type, decided by the device, ids checked ------------------------------

TEST(QueryAnswer, SaysVisibleTheSamplesAndWhetherTheCallerWaited) {
    TwoObjects w;
    ScriptedQueryDevice device(2);  // ready after 2 later commands
    device.setVisibility({1, 0}, w.boxes);
    const QueryId seen = device.issueQuery(w.both);
    const QueryId hidden = device.issueQuery(w.boxes[1]);
    device.drawObject(0);  // 2 commands after `seen`, 1 after `hidden`
    EXPECT_TRUE(device.isQueryReady(seen));
    const QueryAnswer a = device.takeAnswer(seen);
    EXPECT_TRUE(a.visible);
    EXPECT_EQ(a.samples, 1u);
    EXPECT_FALSE(a.waited) << "it was ready";
    const QueryAnswer b = device.takeAnswer(hidden);  // one command short of ready
    EXPECT_FALSE(b.visible);
    EXPECT_EQ(b.samples, 0u);
    EXPECT_TRUE(b.waited);
    EXPECT_EQ(device.counters().results_waited, 1u);
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

// Taking an answer twice, or asking about an id never issued, is a bug in the caller: the test
// devices abort with a message naming the device, the call and the id, in every build.
TEST(QueryAnswerDeathTest, TakingAnAnswerTwiceAbortsWithAMessage) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    TwoObjects w;
    ScriptedQueryDevice device(0);
    device.setVisibility({1, 1}, w.boxes);
    const QueryId id = device.issueQuery(w.boxes[0]);
    device.takeAnswer(id);
    EXPECT_DEATH(
        device.takeAnswer(id),
        "ScriptedQueryDevice::takeAnswer: query id 0 is not in flight \\(already taken\\)");
    EXPECT_DEATH(device.isQueryReady(id), "ScriptedQueryDevice::isQueryReady: query id 0 is not");
}

TEST(QueryAnswerDeathTest, AnIdNeverIssuedAbortsWithAMessage) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    ScriptedQueryDevice scripted(0);
    EXPECT_DEATH(scripted.takeAnswer(7),
                 "ScriptedQueryDevice::takeAnswer: query id 7 was never issued");
    DepthRasterDevice raster(4, 4);
    EXPECT_DEATH(raster.isQueryReady(3), "DepthRasterDevice::isQueryReady: query id 3 was never");
}

}  // namespace
}  // namespace occsim
