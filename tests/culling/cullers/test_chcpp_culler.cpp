// CHC++ (culling/cullers/chcpp_culler.h) on the scripted query device: multiqueries, batching, the
// randomised re-test. No OpenGL.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "culling/cullers/chcpp_culler.h"
#include "culling_fixtures.h"
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
using testing::sameBox;

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

}  // namespace
}  // namespace occsim
