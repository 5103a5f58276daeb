// The bird's-eye picture of a frame's culling: the trace of its decisions (the tracing device and
// the class of every node), then the picture drawn from it. No OpenGL: the culler runs on the
// scripted query device.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <vector>

#include "culling/cullers/basic_cullers.h"
#include "culling_fixtures.h"
#include "occsim/culling/testing/scripted_query_device.h"
#include "sim/output/birds_eye.h"

namespace occsim {
namespace {

// ---- the scene of the classification tests -----------------------------------------------
//
// The eye at (0, 0.5, 0) looks down -z with a 90 degree square frustum. Object 0 touches the
// near plane (so stop-and-wait draws it and its ancestors' objects without a query), 1 is a wall,
// 2 and 3 hide behind it, 4 and 5 lie far to the right outside the frustum, 6 is visible beside
// the wall. With one object per leaf and median splits the tree is (checked by the test):
//   node 0 (root, objects 0 1)
//     node 1 (object 6): node 3 (object 2), node 4 (empty)
//     node 2 (object 4): node 5 (object 3), node 6 (object 5)
const std::vector<Aabb> kBoxes = {
    {{-0.2f, 0.3f, -0.15f}, {0.2f, 0.7f, -0.05f}},
    {{-4, 0, -6}, {4, 1, -5}},
    {{-1, 0, -20}, {0, 1, -19}},
    {{0.5f, 0, -22}, {1.5f, 1, -21}},
    {{60, 0, -10}, {61, 1, -9}},
    {{70, 0, -10}, {71, 1, -9}},
    {{-9, 0, -12}, {-8, 1, -11}},
};
const std::vector<uint8_t> kVisible = {1, 1, 0, 0, 0, 0, 1};

BspTree sceneTree() {
    BspTree tree;
    BspBuildOptions options;
    options.max_objects_per_leaf = 1;
    options.split_rule = BspSplitRule::Median;
    options.looseness = 0.0f;  // plain cells: the straddlers stay in inner nodes, as below
    tree.build(kBoxes, options);
    return tree;
}

CullView sceneView() {
    return testing::makeView({0, 0.5f, 0}, {0, 0.5f, -1}, 90.0f, 0.1f, 100.0f, 1.0f);
}

std::vector<uint32_t> objectsOf(const BspTree& tree, uint32_t node) {
    std::vector<uint32_t> out;
    for (uint32_t o = tree.firstObject(node); o != BspTree::kNone; o = tree.nextObject(o))
        out.push_back(o);
    std::sort(out.begin(), out.end());
    return out;
}

// Stop-and-wait on the scripted device, traced.
FrameTrace traceStopAndWait(const BspTree& tree, const CullView& view) {
    ScriptedQueryDevice device;
    device.setVisibility(kVisible, kBoxes);
    TracingDevice tracer(device);
    StopAndWaitCuller culler;
    culler.reset(tree);
    tracer.beginTrace(7);
    culler.cullAndRender(tree, testing::makeFrame(view, 7, 0.25), tracer);
    tracer.endTrace();
    return tracer.trace();
}

// ---- TracingDevice ------------------------------------------------------------------------

TEST(TracingDevice, RecordsDrawsQueriesResultsAndPendingOnlyWhileTracing) {
    ScriptedQueryDevice inner;
    inner.setVisibility(kVisible, kBoxes);
    TracingDevice tracer(inner);

    const QueryId before = tracer.issueQuery(kBoxes[1]);  // not traced: issued before the trace
    tracer.drawObject(5);
    tracer.beginTrace(3);
    tracer.drawObject(1);
    const Aabb pair[2] = {kBoxes[2], kBoxes[3]};
    const QueryTag pair_tags[2] = {QueryTag::node(3), QueryTag::node(4)};
    const QueryId hidden = tracer.issueQuery(std::span<const Aabb>(pair, 2), pair_tags);
    const QueryId seen = tracer.issueQuery(kBoxes[6]);
    const QueryId left_open = tracer.issueQuery(kBoxes[0]);
    EXPECT_EQ(tracer.takeAnswer(before).samples, 1u);  // the wall is visible
    EXPECT_FALSE(tracer.takeAnswer(hidden).visible);
    EXPECT_EQ(tracer.takeAnswer(seen).samples, 1u);
    EXPECT_EQ(tracer.isQueryReady(left_open), inner.isQueryReady(left_open));  // forwarded
    tracer.endTrace();
    tracer.drawObject(6);  // after the trace: not recorded
    tracer.takeAnswer(left_open);

    const FrameTrace& t = tracer.trace();
    EXPECT_EQ(t.frame, 3u);
    EXPECT_EQ(t.drawn_objects, std::vector<uint32_t>{1});
    ASSERT_EQ(t.queries.size(), 3u);
    EXPECT_EQ(t.queries[0].boxes.size(), 2u);
    EXPECT_EQ(t.queries[0].subjects, (std::vector<QueryTag>{QueryTag::node(3), QueryTag::node(4)}));
    EXPECT_TRUE(t.queries[0].fetched);
    EXPECT_EQ(t.queries[0].samples, 0u);
    EXPECT_FALSE(t.queries[0].visible);
    EXPECT_TRUE(t.queries[1].fetched);
    EXPECT_EQ(t.queries[1].samples, 1u);
    EXPECT_TRUE(t.queries[1].visible);
    EXPECT_FALSE(t.queries[2].fetched);  // never fetched while tracing: pending
    EXPECT_EQ(t.pendingQueries(), 1u);
    EXPECT_EQ(t.earlier_results_fetched, 1u);

    // The wrapped device does the work; the tracer reports its counters, so they are true.
    EXPECT_EQ(inner.counters().objects_drawn, 3u);
    EXPECT_EQ(inner.counters().queries_issued, 4u);
    EXPECT_EQ(tracer.counters().objects_drawn, 3u);
    EXPECT_EQ(tracer.counters().queries_issued, 4u);
    tracer.resetCounters();
    EXPECT_EQ(inner.counters().objects_drawn, 0u);
}

// ---- classifyNodes ------------------------------------------------------------------------

TEST(ClassifyNodes, StopAndWaitOnAScriptedSceneGivesTheExpectedClassPerNode) {
    const BspTree tree = sceneTree();
    // The structure the expectations below rely on.
    ASSERT_EQ(tree.nodeCount(), 7u);
    EXPECT_EQ(objectsOf(tree, 0), (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(objectsOf(tree, 1), std::vector<uint32_t>{6});
    EXPECT_EQ(objectsOf(tree, 2), std::vector<uint32_t>{4});
    EXPECT_EQ(objectsOf(tree, 3), std::vector<uint32_t>{2});
    EXPECT_TRUE(objectsOf(tree, 4).empty());
    EXPECT_EQ(objectsOf(tree, 5), std::vector<uint32_t>{3});
    EXPECT_EQ(objectsOf(tree, 6), std::vector<uint32_t>{5});
    EXPECT_EQ(tree.node(5).parent, 2u);
    EXPECT_EQ(tree.node(6).parent, 2u);

    const CullView view = sceneView();
    const FrameTrace trace = traceStopAndWait(tree, view);
    const std::vector<NodeClass> got = classifyNodes(tree, view, trace);
    const std::vector<NodeClass> want = {
        NodeClass::DrawnWithoutQuery,  // 0: the near plane cuts its box: drawn, never queried
        NodeClass::DrawnAfterQuery,    // 1: queried, visible, object 6 drawn
        NodeClass::OcclusionCulled,    // 2: behind the wall (its bounds reach into the frustum)
        NodeClass::OcclusionCulled,    // 3: object 2 behind the wall
        NodeClass::Empty,              // 4
        NodeClass::NotReached,         // 5: in the frustum, below the occluded node 2
        NodeClass::FrustumCulled,      // 6: object 5, far right
    };
    ASSERT_EQ(got.size(), want.size());
    for (size_t n = 0; n < want.size(); ++n) {
        EXPECT_EQ(got[n], want[n]) << "node " << n << ": got " << nodeClassName(got[n]) << ", want "
                                   << nodeClassName(want[n]);
    }
}

TEST(ClassifyNodes, MultiqueriesCountForEveryNodeTheyWereTaggedWith) {
    const BspTree tree = sceneTree();
    const CullView view = sceneView();
    FrameTrace trace;
    // One multiquery over nodes 1 and 5 that came back 0; a pending query on node 3; nothing drawn.
    trace.queries.push_back(
        {{tree.bounds(1), tree.bounds(5)}, {QueryTag::node(1), QueryTag::node(5)}, true, 0});
    trace.queries.push_back({{tree.bounds(3)}, {QueryTag::node(3)}, false, 0});
    const std::vector<NodeClass> got = classifyNodes(tree, view, trace);
    EXPECT_EQ(got[0], NodeClass::Passed);           // visited, nothing of its own drawn
    EXPECT_EQ(got[1], NodeClass::OcclusionCulled);  // first box of the multiquery
    EXPECT_EQ(got[5], NodeClass::OcclusionCulled);  // second box
    EXPECT_EQ(got[3], NodeClass::NotReached);       // below node 1; its query never answered
    EXPECT_EQ(got[2], NodeClass::Passed);
    EXPECT_EQ(got[6], NodeClass::FrustumCulled);

    // The tag decides, not the box: a per-object query with a node's very bounds changes
    // nothing, and an occluded query on a node's own objects culls nothing (they were drawn).
    FrameTrace other;
    other.queries.push_back({{tree.bounds(1)}, {QueryTag::object(6)}, true, 0});
    other.queries.push_back({{tree.bounds(2)}, {QueryTag::nodeObjects(2)}, true, 0});
    EXPECT_EQ(classifyNodes(tree, view, other)[1], NodeClass::Passed);
    EXPECT_EQ(classifyNodes(tree, view, other)[2], NodeClass::Passed);
}

// hzb and masked decide without queries (a depth pyramid, a software buffer): what they left
// out inside the frustum is culled by their own test, the topmost node of it named so, not
// "passed through" as if nothing had culled it.
TEST(ClassifyNodes, AFrameWithoutQueriesNamesWhatItsOwnTestCulled) {
    const BspTree tree = sceneTree();
    const CullView view = sceneView();
    FrameTrace trace;
    trace.drawn_objects = {0, 1, 6};  // nodes 0 and 1 drawn; 2 (4), 3 (2) and 5 (3) not
    const std::vector<NodeClass> got = classifyNodes(tree, view, trace);
    EXPECT_EQ(got[0], NodeClass::DrawnWithoutQuery);
    EXPECT_EQ(got[1], NodeClass::DrawnWithoutQuery);
    EXPECT_EQ(got[2], NodeClass::CulledWithoutQuery);
    EXPECT_EQ(got[3], NodeClass::CulledWithoutQuery) << "below a drawn node, culled itself";
    EXPECT_EQ(got[5], NodeClass::NotReached) << "below the culled node 2";
    EXPECT_EQ(got[6], NodeClass::FrustumCulled);
    EXPECT_STREQ(nodeClassName(NodeClass::CulledWithoutQuery), "culled without query");
    // With a query in the frame, the query says what was culled, as before.
    trace.queries.push_back({{tree.bounds(1)}, {QueryTag::node(1)}, true, true, 5});
    EXPECT_EQ(classifyNodes(tree, view, trace)[2], NodeClass::Passed);
}

// ---- renderBirdsEye -----------------------------------------------------------------------

struct Picture {
    std::vector<uint8_t> rgba;
    uint32_t width, height;

    size_t count(Rgb c) const {
        size_t n = 0;
        for (size_t i = 0; i + 3 < rgba.size(); i += 4) {
            n += rgba[i] == c.r && rgba[i + 1] == c.g && rgba[i + 2] == c.b;
        }
        return n;
    }
};

Picture renderScene(bool legend, std::vector<NodeClass>* classes_out = nullptr) {
    static const BspTree tree = sceneTree();
    const CullView view = sceneView();
    static FrameTrace trace;
    trace = traceStopAndWait(tree, view);
    static std::vector<NodeClass> classes;
    classes = classifyNodes(tree, view, trace);
    if (classes_out) *classes_out = classes;
    BirdsEyeInput in;
    in.tree = &tree;
    in.object_boxes = kBoxes;
    in.drawn_objects = trace.drawn_objects;
    in.node_classes = classes;
    in.view = view;
    in.forward = {0, 0, -1};
    in.fov_y_rad = glm::radians(90.0f);
    in.aspect = 1.0f;
    in.near_m = 0.1f;
    in.far_m = 100.0f;
    in.title = "frame 7 stop-and-wait";
    in.draw_legend = legend;
    const uint32_t w = 640, h = 400;
    return {renderBirdsEye(in, w, h), w, h};
}

TEST(BirdsEye, ReturnsRgbaOfThePictureSizeWithTheCameraAndEveryClassPresent) {
    std::vector<NodeClass> classes;
    const Picture p = renderScene(false, &classes);
    ASSERT_EQ(p.rgba.size(), size_t{p.width} * p.height * 4);
    for (size_t i = 3; i < p.rgba.size(); i += 4) ASSERT_EQ(p.rgba[i], 255) << "opaque";
    EXPECT_GE(p.count(kCameraColour), 20u) << "the camera dot";
    EXPECT_GT(p.count(kDrawnObjectColour), 0u);
    EXPECT_GT(p.count(kHiddenObjectColour), 0u);
    // Without the legend, a class colour can only come from a node outline.
    for (NodeClass c : classes) {
        if (c == NodeClass::Empty) continue;
        EXPECT_GT(p.count(nodeClassColour(c)), 0u) << nodeClassName(c);
    }
    EXPECT_EQ(p.count(nodeClassColour(NodeClass::Passed)), 0u) << "no node passed through";
}

TEST(BirdsEye, IsDeterministicAndTheLegendAddsItsSwatches) {
    const Picture a = renderScene(true), b = renderScene(true);
    EXPECT_EQ(a.rgba, b.rgba);
    // The legend shows every class, present or not.
    EXPECT_GT(a.count(nodeClassColour(NodeClass::Passed)), 0u);
}

TEST(BirdsEye, TheCameraDotSitsAtTheEyeInATopViewWithMinusZUp) {
    const Picture p = renderScene(false);
    // Find the camera dot's centre (mean of its pixels), rows counted from the top.
    double sx = 0, sy = 0, n = 0;
    for (uint32_t y = 0; y < p.height; ++y) {
        for (uint32_t x = 0; x < p.width; ++x) {
            const uint8_t* px = &p.rgba[(size_t{p.height - 1 - y} * p.width + x) * 4];
            if (px[0] == kCameraColour.r && px[1] == kCameraColour.g && px[2] == kCameraColour.b) {
                sx += x;
                sy += y;
                ++n;
            }
        }
    }
    ASSERT_GT(n, 0);
    // The eye (z = 0) is the largest z of the scene: the bottom of the fitted region. The scene
    // runs from x = -9 to 71, so the eye at x = 0 is in the left part.
    EXPECT_GT(sy / n, 0.6 * p.height);
    EXPECT_LT(sx / n, 0.4 * p.width);
}

// A drawn ground slab under every object (a city's ground, a library's floor) lies under them in
// the picture: the objects that were not drawn stay visible on it.
TEST(BirdsEye, ADrawnGroundSlabHidesNoObjectThatWasNotDrawn) {
    auto hiddenPixels = [](bool with_ground) {
        std::vector<Aabb> boxes = kBoxes;
        if (with_ground) boxes.push_back({{-12, -0.1f, -25}, {75, 0, 3}});
        BspTree tree;
        BspBuildOptions options;
        options.max_objects_per_leaf = 1;
        tree.build(boxes, options);
        std::vector<uint32_t> drawn = {0, 1, 6};
        if (with_ground) drawn.push_back(7);
        const std::vector<NodeClass> classes(tree.nodeCount(), NodeClass::Empty);
        BirdsEyeInput in;
        in.tree = &tree;
        in.object_boxes = boxes;
        in.drawn_objects = drawn;
        in.node_classes = classes;
        in.view = sceneView();
        in.draw_legend = false;
        const Picture p{renderBirdsEye(in, 640, 400), 640, 400};
        return p.count(kHiddenObjectColour);
    };
    const size_t without = hiddenPixels(false), with = hiddenPixels(true);
    ASSERT_GT(without, 0u);
    EXPECT_GT(with, without / 2) << "the ground slab covers the hidden objects";
}

// A level whose big floor box is drawn every frame is not one yellow field: the floor is outlined
// over a faint tint, so the drawn objects on it stand out, each in full, and the floor still shows
// as drawn (its outline).
TEST(BirdsEye, ADrawnFloorIsOutlinedSoTheDrawnObjectsOnItStandOut) {
    auto picture = [](bool floor_drawn) {
        std::vector<Aabb> boxes = kBoxes;
        boxes.push_back({{-12, -0.1f, -25}, {75, 0, 3}});  // the floor under every object
        BspTree tree;
        BspBuildOptions options;
        options.max_objects_per_leaf = 1;
        tree.build(boxes, options);
        std::vector<uint32_t> drawn = {0, 1, 6};
        if (floor_drawn) drawn.push_back(7);
        const std::vector<NodeClass> classes(tree.nodeCount(), NodeClass::Empty);
        BirdsEyeInput in;
        in.tree = &tree;
        in.object_boxes = boxes;
        in.drawn_objects = drawn;
        in.node_classes = classes;
        in.view = sceneView();
        in.draw_legend = false;
        return Picture{renderBirdsEye(in, 640, 400), 640, 400};
    };
    const Picture hidden_floor = picture(false), drawn_floor = picture(true);
    const size_t objects = hidden_floor.count(kDrawnObjectColour);
    ASSERT_GT(objects, 0u);
    const size_t yellow = drawn_floor.count(kDrawnObjectColour);
    EXPECT_LT(yellow, size_t{640} * 400 / 5) << "not one yellow field";
    EXPECT_GT(yellow, objects) << "the floor's outline shows it drawn";
    // Every drawn object keeps its own yellow pixels, whole, on the drawn floor, and the floor
    // between them is not yellow.
    size_t floor_pixels = 0;
    for (size_t i = 0; i < hidden_floor.rgba.size(); i += 4) {
        const auto colour = [&](const Picture& p) {
            return Rgb{p.rgba[i], p.rgba[i + 1], p.rgba[i + 2]};
        };
        if (colour(hidden_floor) == kDrawnObjectColour) {
            ASSERT_EQ(colour(drawn_floor), kDrawnObjectColour) << "an object pixel, " << i / 4;
        }
        floor_pixels += colour(hidden_floor) != kDrawnObjectColour &&
                        colour(drawn_floor) != kDrawnObjectColour &&
                        colour(drawn_floor) != kBirdsEyeBackground;
    }
    EXPECT_GT(floor_pixels, size_t{640} * 400 / 4) << "the floor shows, tinted, under them";
}

}  // namespace
}  // namespace occsim
