// The reference cullers (culling/cullers/basic_cullers.h): frustum culling, stop-and-wait, the
// Ideal oracle, on the scripted query device.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "culling/cullers/basic_cullers.h"
#include "culling_fixtures.h"
#include "occsim/culling/geometry/query_box.h"
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
    EXPECT_TRUE(findCuller("ideal")->oracle) << "the registry says it needs ground truth";
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

// The limit of box tests: what ground truth saw, then every other box in the frustum queried
// against it; on the scripted device a box shows samples when it overlaps a visible object's.
TEST(IdealBoxCuller, DrawsWhatGroundTruthSawAndEveryObjectWhoseBoxShows) {
    std::vector<Aabb> boxes = randomBoxes(500, 4);
    // Hidden objects whose boxes overlap a visible one's: their boxes show samples.
    for (uint32_t o = 0; o < 500; o += 7) {
        const glm::vec3 shift = 0.25f * extent(boxes[o]);
        boxes.push_back({boxes[o].min + shift, boxes[o].max + shift});
    }
    const BspTree tree = buildTree(boxes);
    const CullView view = makeView({0, 5, 0}, {0, 0, -100});
    const std::set<uint32_t> frustum = inFrustum(boxes, view.frustum);
    std::vector<uint8_t> truth(boxes.size());
    for (uint32_t o : frustum) truth[o] = o < 500 && o % 7 == 0;
    CullFrame frame = makeFrame(view, 0, 0.0);
    frame.ground_truth_visible = truth;
    ScriptedQueryDevice device(3);
    device.setVisibility(truth, boxes);
    IdealBoxCuller culler;
    EXPECT_TRUE(findCuller("ideal-box")->oracle);
    EXPECT_FALSE(findCuller("ideal-box")->issues_queries) << "exact queries: no knobs";
    culler.cullAndRender(tree, frame, device);
    const std::set<uint32_t> drawn(device.drawnObjects().begin(), device.drawnObjects().end());
    EXPECT_EQ(drawn.size(), device.drawnObjects().size()) << "each object drawn once";
    size_t hidden = 0, box_visible = 0;
    for (uint32_t o : frustum) {
        bool overlaps = false;
        for (uint32_t v : frustum) overlaps |= truth[v] && occsim::overlaps(boxes[o], boxes[v]);
        if (truth[o]) {
            EXPECT_TRUE(drawn.count(o)) << "visible object " << o << " missed";
        } else if (!nearPlaneTouchesBox(boxes[o], view.eye, view.near_radius)) {
            EXPECT_EQ(drawn.count(o) != 0, overlaps) << "object " << o;
            hidden += !overlaps;
            box_visible += overlaps;
        }
    }
    for (uint32_t o : drawn) EXPECT_TRUE(frustum.count(o)) << o;
    EXPECT_GT(hidden, 0u);
    EXPECT_GT(box_visible, 0u) << "the scene tests both ways";
    EXPECT_EQ(device.counters().queries_issued, hidden + box_visible);
}

}  // namespace
}  // namespace occsim
