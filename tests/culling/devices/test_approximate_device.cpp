// The approximating device (occsim/culling/devices/approximate_device.h): a pixel threshold and
// stale results for any culler that issues queries.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "culling/cullers/statistical_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/devices/approximate_device.h"
#include "occsim/culling/registry/registry.h"
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
using testing::TwoObjects;

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

TEST(ApproximateDevice, OffersConditionalRenderingOnlyWhileItApproximatesNothing) {
    ScriptedQueryDevice inner;
    EXPECT_NE(ApproximateDevice(inner, {}).conditionalRendering(), nullptr);
    EXPECT_EQ(ApproximateDevice(inner, {4, false}).conditionalRendering(), nullptr)
        << "a threshold cannot reach a condition the device evaluates";
    EXPECT_EQ(ApproximateDevice(inner, {0, true}).conditionalRendering(), nullptr);
    inner.offerConditionalRendering(false);
    EXPECT_EQ(ApproximateDevice(inner, {}).conditionalRendering(), nullptr);
}

}  // namespace
}  // namespace occsim
