// What a person looks at after a benchmark: the trace of one frame's culling decisions, the
// bird's-eye picture drawn from it, report.md and the gnuplot charts. No OpenGL: the culler runs
// on the scripted query device.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "culling/cullers/basic_cullers.h"
#include "culling_fixtures.h"
#include "occsim/culling/devices/tracing_device.h"
#include "occsim/culling/testing/scripted_query_device.h"
#include "sim/output/birds_eye.h"
#include "sim/output/error_picture.h"
#include "sim/output/fixed_text.h"
#include "sim/output/markdown_report.h"
#include "sim/output/plots.h"
#include "sim/output/report.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

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

// ---- markdownReport -----------------------------------------------------------------------

RunRecord record(const std::string& label, const std::string& algorithm, double mean_ms,
                 double error_mean, bool pareto) {
    RunRecord r;
    r.algorithm = findCuller(algorithm);
    r.pareto = pareto;
    RunSummary& s = r.summary;
    s.label = label;
    s.frames = 30;
    s.timed_frames = 25;
    s.frame_ms = {mean_ms, mean_ms, mean_ms * 1.2, mean_ms * 0.8, mean_ms * 1.5};
    s.frame_ms_mean_min = s.frame_ms_mean_max = mean_ms;
    s.queries_mean = algorithm == "vfc" || algorithm == "ideal" ? 0 : 42;
    s.triangles_mean = 1000 * mean_ms;
    s.objects_mean = 10 * mean_ms;
    s.error_measured = true;
    s.error_pixels_mean = error_mean;
    s.error_pixels_total = static_cast<int64_t>(error_mean * 30);
    for (uint32_t f = 0; f < 30; ++f) {
        FrameStats fs;
        fs.frame = f;
        fs.frame_ms = mean_ms + (f % 5);
        fs.queries = static_cast<uint64_t>(s.queries_mean) + f;
        fs.triangles = static_cast<uint64_t>(s.triangles_mean) + 100 * f;
        r.frames.push_back(fs);
    }
    return r;
}

std::vector<RunRecord> sampleRuns() {
    return {record("vfc", "vfc", 20.0, 0.0, false),
            record("statistical threshold=4", "statistical", 12.0, 3.5, true),
            record("chc", "chc", 14.0, 0.0, true), record("ideal", "ideal", 6.0, 0.0, false)};
}

TEST(MarkdownReport, HasTheHeaderTheTableRowsThePictureLinksAndHowToRead) {
    BenchResult result;
    result.runs = sampleRuns();
    RunMetadata& c = result.metadata;
    c.scenario_name = "teapots-small";
    c.scenario_file = "scenarios/small/teapots-small.json";
    c.frames = 30;
    c.warmup_frames = 5;
    c.error_measured = true;
    c.hardware_threads = 2;
    c.renderer = "llvmpipe (test)";
    c.width = 200;
    c.height = 150;
    c.command_line = "occsim bench scenarios/small/teapots-small.json --error --plots";
    c.sweep = Sweep{"", "threshold", {0, 4}};
    ReportFiles files;
    files.plot_files = {"plot-frame-time.png", "plot-frame-time.svg", "plot-time-vs-error.png"};
    files.birds_eye_files = {"birds-eye-chc-frame-00020.png"};
    const std::string md = markdownReport(result, files);

    EXPECT_NE(md.find("# occsim bench: teapots-small"), std::string::npos);
    EXPECT_NE(md.find(c.command_line), std::string::npos);
    EXPECT_NE(md.find("2 hardware threads"), std::string::npos);
    EXPECT_NE(md.find("llvmpipe (test)"), std::string::npos);
    EXPECT_NE(md.find("threshold = 0, 4"), std::string::npos);
    EXPECT_NE(md.find("first 5 frames are warm-up"), std::string::npos);
    EXPECT_NE(md.find("Ground-truth rendering, PNG writing and statistics I/O"), std::string::npos);
    // The table: same columns as the text table, one row per configuration, Pareto marked.
    const ComparisonTable t = comparisonTable(result.runs);
    std::string header = "|";
    for (const auto& h : t.header) header += " " + h + " |";
    EXPECT_NE(md.find(header), std::string::npos) << md;
    EXPECT_NE(md.find("| vfc | 20.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| **statistical threshold=4** | 12.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| **chc** | 14.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| ideal | 6.00 |"), std::string::npos) << md;
    EXPECT_NE(md.find("1.67x"), std::string::npos) << "speedup of statistical over VFC";
    // Pictures: the PNGs as images, the SVG linked; only the files named.
    EXPECT_NE(md.find("![Frame time per frame](plot-frame-time.png)"), std::string::npos);
    EXPECT_NE(md.find("(plot-frame-time.svg)"), std::string::npos);
    EXPECT_NE(md.find("![Time against error](plot-time-vs-error.png)"), std::string::npos);
    EXPECT_EQ(md.find("plot-queries-triangles"), std::string::npos);
    EXPECT_NE(md.find("](birds-eye-chc-frame-00020.png)"), std::string::npos);
    EXPECT_NE(md.find("## How to read this"), std::string::npos);
    EXPECT_NE(md.find("popping"), std::string::npos);
}

// One error pixel in 240 frames is an error: no cell of the table (console and report.md alike)
// prints a figure that is not zero as 0.0.
TEST(ComparisonTable, ANonZeroFigureNeverPrintsAsZero) {
    EXPECT_EQ(fixedNonZero(1.0 / 240, 1), "<0.1");
    EXPECT_EQ(fixedNonZero(0.3, 0), "<1");
    EXPECT_EQ(fixedNonZero(-0.001, 2), ">-0.01");
    EXPECT_EQ(fixedNonZero(0.0, 1), "0.0");
    EXPECT_EQ(fixedNonZero(0.06, 1), "0.1");
    EXPECT_EQ(fixedNonZero(2.25, 1), fixed(2.25, 1));
    BenchResult result;
    result.runs = {record("vfc", "vfc", 20.0, 0.0, false),
                   record("async", "async", 10.0, 0.0, true)};
    RunSummary& s = result.runs[1].summary;
    s.frames = 240;
    s.error_pixels_total = 1;
    s.error_pixels_worst = 1;
    s.error_pixels_mean = 1.0 / 240;
    s.queries_mean = 0.02;
    const ComparisonTable t = comparisonTable(result.runs);
    auto column = [&](const std::string& name) {
        return static_cast<size_t>(std::find(t.header.begin(), t.header.end(), name) -
                                   t.header.begin());
    };
    ASSERT_LT(column("err px/fr"), t.header.size());
    EXPECT_EQ(t.rows[1][column("err px/fr")], "<0.1");
    EXPECT_EQ(t.rows[1][column("queries/fr")], "<0.1");
    EXPECT_EQ(t.rows[0][column("err px/fr")], "0.0") << "zero stays zero";
    EXPECT_NE(formatComparisonTable(result.runs).find("<0.1"), std::string::npos);
    EXPECT_NE(markdownReport(result, ReportFiles{}).find("| <0.1 |"), std::string::npos);
}

// ---- writePlots ---------------------------------------------------------------------------

fs::path freshDir(const std::string& name) {
    const fs::path p = fs::temp_directory_path() /
                       ("occsim-report-outputs-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(p);
    return p;
}

// Sets PATH for the scope of a test and puts the old value back.
class ScopedPath {
  public:
    explicit ScopedPath(const std::string& value) {
        if (const char* old = std::getenv("PATH")) old_ = old;
        ::setenv("PATH", value.c_str(), 1);
    }
    ~ScopedPath() {
        if (old_)
            ::setenv("PATH", old_->c_str(), 1);
        else
            ::unsetenv("PATH");
    }
    ScopedPath(const ScopedPath&) = delete;
    ScopedPath& operator=(const ScopedPath&) = delete;

  private:
    std::optional<std::string> old_;
};

void writeExecutable(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
    ::chmod(path.c_str(), 0755);
}

std::vector<std::string> filesIn(const fs::path& dir) {
    std::vector<std::string> out;
    if (!fs::exists(dir)) return out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

// A run records the load average before and after it; one on a machine busier than its hardware
// threads says so on the console, in report.md and in summary.json.
TEST(RunHeadline, SaysTheLoadAndWarnsWhenTheMachineWasBusy) {
    BenchResult result;
    result.runs = sampleRuns();
    RunMetadata& m = result.metadata;
    m.scenario_name = "teapots-small";
    m.frames = 40;
    m.hardware_threads = 2;
    m.load_before = {0.5, 0.4, 0.3};
    m.load_after = {1.25, 0.6, 0.4};
    EXPECT_NE(runHeadline(result).find(
                  "machine: 2 hardware threads, load average 0.50 before the run, 1.25 after"),
              std::string::npos)
        << runHeadline(result);
    EXPECT_EQ(runHeadline(result).find("busy machine"), std::string::npos);
    EXPECT_FALSE(m.busyMachine());
    m.load_after = {3.5, 3.0, 1.0};
    EXPECT_FALSE(m.busyMachine()) << "after a run its own threads count in the load";
    m.load_after = {5.5, 3.0, 1.0};
    EXPECT_TRUE(m.busyMachine());
    m.load_after = {1.0, 1.0, 1.0};
    m.load_before = {2.5, 1.0, 1.0};
    EXPECT_TRUE(m.busyMachine()) << "other work when the run began";
    m.load_after = {5.5, 3.0, 1.0};
    EXPECT_NE(runHeadline(result).find("busy machine: other work ran beside this run"),
              std::string::npos);
    EXPECT_NE(markdownReport(result, {}).find("**busy: other work ran beside this run"),
              std::string::npos);
    const nlohmann::json summary = summaryJson(result);
    EXPECT_EQ(summary["machine"]["busy"], true);
    EXPECT_EQ(summary["machine"]["load_average_after"][0], 5.5);
    EXPECT_EQ(summary["machine"]["load_average_before"].size(), 3u);
}

TEST(Plots, WithoutGnuplotOnPathSaysSoAndWritesNothing) {
    const fs::path empty_bin = freshDir("empty-bin");
    fs::create_directories(empty_bin);
    const fs::path out = freshDir("no-gnuplot");
    PlotResult r;
    {
        ScopedPath path(empty_bin.string());
        r = writePlots(sampleRuns(), out);
    }
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.message,
              "plots skipped: gnuplot not found; install the Debian package gnuplot-nox");
    EXPECT_TRUE(r.files.empty());
    EXPECT_FALSE(fs::exists(out)) << "nothing written, not even the folder";
}

TEST(Plots, AFailingGnuplotLeavesNoPictureNotEvenAHalfWrittenOne) {
    const fs::path bin = freshDir("failing-bin");
    fs::create_directories(bin);
    // Writes a partial file under every temporary name the script asks for, then fails.
    writeExecutable(bin / "gnuplot",
                    "#!/bin/sh\n"
                    "for f in $(grep -o '\\.plot-[a-z-]*\\.[a-z]*\\.tmp-[0-9]*' \"$1\"); do\n"
                    "  printf partial > \"$f\"\n"
                    "done\n"
                    "echo '\"plots.gp\" line 9: something broke' >&2\n"
                    "exit 1\n");
    const fs::path out = freshDir("failing");
    PlotResult r;
    {
        ScopedPath path(bin.string() + ":/usr/bin:/bin");
        r = writePlots(sampleRuns(), out);
    }
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.message.find("plots failed"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("something broke"), std::string::npos) << r.message;
    EXPECT_TRUE(r.files.empty());
    for (const std::string& f : filesIn(out)) {
        EXPECT_TRUE(f.ends_with(".dat") || f == "plots.gp") << "left behind: " << f;
    }
}

TEST(Plots, WithGnuplotWritesNonEmptyPngAndSvgOfEveryChart) {
    if (!findOnPath("gnuplot"))
        GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
    const fs::path out = freshDir("real");
    const PlotResult r = writePlots(sampleRuns(), out);
    ASSERT_TRUE(r.ok) << r.message;
    const std::vector<std::string> want = {
        "plot-frame-time.png",    "plot-frame-time.svg",        "plot-time-vs-error.png",
        "plot-time-vs-error.svg", "plot-queries-triangles.png", "plot-queries-triangles.svg"};
    EXPECT_EQ(r.files, want);
    for (const std::string& f : want) {
        ASSERT_TRUE(fs::exists(out / f)) << f;
        EXPECT_GT(fs::file_size(out / f), 1000u) << f;
        std::ifstream in(out / f, std::ios::binary);
        std::string head(8, '\0');
        in.read(head.data(), 8);
        if (f.ends_with(".png"))
            EXPECT_EQ(head.substr(1, 3), "PNG") << f;
        else
            EXPECT_TRUE(head.starts_with("<?xml") || head.starts_with("<svg")) << f;
    }
    for (const std::string& f : filesIn(out)) EXPECT_EQ(f.find(".tmp-"), std::string::npos) << f;
}

// The worst-frame picture: culled | ground truth | ground truth dimmed with error pixels in
// magenta and tie pixels in yellow (docs/error.md).
TEST(ErrorPicture, MarksErrorsAndTiesInTheirOwnColours) {
    const uint32_t w = 3, h = 1;
    ErrorFrame frame;
    frame.culled_rgba.assign(w * h * 4, 30);
    frame.truth_rgba.assign(w * h * 4, 90);
    frame.culled_ids = {1, 2, 0};
    frame.truth_ids = {1, 3, 4};
    frame.differences = {static_cast<uint8_t>(PixelDifference::Same),
                         static_cast<uint8_t>(PixelDifference::Tie),
                         static_cast<uint8_t>(PixelDifference::Error)};
    const std::vector<uint8_t> picture = composeErrorPicture(frame, w, h);
    ASSERT_EQ(picture.size(), size_t{3 * w} * h * 4);
    const uint8_t* marks = picture.data() + 2 * w * 4;
    EXPECT_EQ(marks[0], 30) << "an unchanged pixel is ground truth dimmed";
    EXPECT_EQ(std::vector<uint8_t>(marks + 4, marks + 7),
              std::vector<uint8_t>(kTieColour, kTieColour + 3));
    EXPECT_EQ(std::vector<uint8_t>(marks + 8, marks + 11),
              std::vector<uint8_t>(kErrorColour, kErrorColour + 3));
    frame.differences.pop_back();
    EXPECT_THROW(composeErrorPicture(frame, w, h), std::invalid_argument);
}

// The picture report.md shows: the panels one above the other, each frame pixel a square of
// errorPictureScale() pixels, each panel under a label in black on white.
TEST(ErrorPicture, TheLabelledPictureShowsEachErrorPixelAsASquareUnderALabel) {
    const uint32_t w = 100, h = 2;  // scale 8: the most
    ErrorFrame frame;
    frame.culled_rgba.assign(w * h * 4, 30);
    frame.truth_rgba.assign(w * h * 4, 90);
    frame.culled_ids.assign(w * h, 1);
    frame.truth_ids.assign(w * h, 1);
    frame.differences.assign(w * h, static_cast<uint8_t>(PixelDifference::Same));
    frame.differences[w + 7] = static_cast<uint8_t>(PixelDifference::Error);  // x 7, row 1
    frame.error_pixels = 1;
    const uint32_t scale = errorPictureScale(w);
    ASSERT_EQ(scale, 8u);
    EXPECT_EQ(errorPictureScale(200), 4u);
    EXPECT_EQ(errorPictureScale(4000), 1u);
    const LabelledPicture picture = labelledErrorPicture(frame, w, h, "statistical");
    ASSERT_EQ(picture.rgba.size(), size_t{picture.width} * picture.height * 4);
    const uint32_t panel = (picture.height) / 3;  // label strip + scaled frame
    const uint32_t band = panel - h * scale;
    EXPECT_GT(band, 14u) << "a label strip above every panel";
    EXPECT_GE(picture.width, w * scale);
    // Rows are bottom-up: the last panel (the difference) is at the bottom; its frame row 1
    // (bottom-up, as the frame's) is the upper one of its two scaled rows.
    auto at = [&](uint32_t x, uint32_t y_from_bottom) {
        const uint8_t* p = picture.rgba.data() + (size_t{y_from_bottom} * picture.width + x) * 4;
        return std::vector<uint8_t>(p, p + 3);
    };
    const std::vector<uint8_t> magenta(kErrorColour, kErrorColour + 3);
    int marked = 0;
    for (uint32_t y = 0; y < 2 * scale; ++y) {
        for (uint32_t x = 0; x < w * scale; ++x) marked += at(x, y) == magenta;
    }
    EXPECT_EQ(marked, static_cast<int>(scale * scale)) << "one error pixel, one square";
    for (uint32_t d = 0; d < scale; ++d) {
        EXPECT_EQ(at(7 * scale + d, scale + d), magenta) << d;
    }
    int ink = 0;  // the difference panel's label, in black above it
    for (uint32_t y = 2 * scale; y < 2 * scale + band; ++y) {
        for (uint32_t x = 0; x < picture.width; ++x)
            ink += at(x, y) == std::vector<uint8_t>{0, 0, 0};
    }
    EXPECT_GT(ink, 100) << "a label";
}

// The worst frame's error pixels are found at any size: every cluster of them is ringed, a few
// picture pixels outside it, and every object ground truth shows there is labelled beside it.
TEST(ErrorPicture, EveryClusterOfErrorPixelsIsRingedAndEachMissedObjectLabelled) {
    const uint32_t w = 60, h = 40;  // scale 8
    ErrorFrame frame;
    frame.culled_rgba.assign(w * h * 4, 30);
    frame.truth_rgba.assign(w * h * 4, 90);
    frame.culled_ids.assign(w * h, 1);
    frame.truth_ids.assign(w * h, 1);
    frame.differences.assign(w * h, static_cast<uint8_t>(PixelDifference::Same));
    auto mark = [&](uint32_t x, uint32_t y, uint32_t truth_id) {
        frame.differences[y * w + x] = static_cast<uint8_t>(PixelDifference::Error);
        frame.truth_ids[y * w + x] = truth_id;
    };
    for (uint32_t x = 10; x <= 12; ++x) {  // object 4: 3 x 2 pixels
        mark(x, 5, 5);
        mark(x, 6, 5);
    }
    mark(45, 30, 8);  // object 7: one pixel
    frame.differences[20 * w + 30] = static_cast<uint8_t>(PixelDifference::Tie);
    frame.error_pixels = 7;

    const std::vector<PixelCluster> clusters = errorClusters(frame.differences, w, h);
    ASSERT_EQ(clusters.size(), 2u);
    EXPECT_EQ(clusters[0].pixels, 6u);
    EXPECT_EQ(
        std::vector<uint32_t>({clusters[0].x0, clusters[0].y0, clusters[0].x1, clusters[0].y1}),
        std::vector<uint32_t>({10, 5, 12, 6}));
    EXPECT_EQ(clusters[1].pixels, 1u);
    const std::vector<MissedInFrame> missed = missedObjects(frame, w, h);
    ASSERT_EQ(missed.size(), 2u);
    EXPECT_EQ(missed[0].object, 4u);
    EXPECT_EQ(missed[1].object, 7u);
    EXPECT_EQ(missed[1].where.pixels, 1u);

    const uint32_t scale = errorPictureScale(w);
    ASSERT_EQ(scale, 8u);
    auto greenIn = [](const LabelledPicture& p, uint32_t x0, uint32_t y0, uint32_t x1,
                      uint32_t y1) {
        int n = 0;
        for (uint32_t y = y0; y <= y1; ++y) {
            for (uint32_t x = x0; x <= x1; ++x) {
                const uint8_t* c = p.rgba.data() + (size_t{y} * p.width + x) * 4;
                n += c[0] == kRingColour[0] && c[1] == kRingColour[1] && c[2] == kRingColour[2];
            }
        }
        return n;
    };
    const LabelledPicture picture = labelledErrorPicture(frame, w, h, "async");
    // The difference panel is the bottom one; frame pixel (x, y) covers picture pixels
    // [8x, 8x + 7] x [8y, 8y + 7], rows bottom-up. The one-pixel cluster at (45, 30):
    const uint32_t x0 = 45 * scale, x1 = x0 + scale - 1, y0 = 30 * scale, y1 = y0 + scale - 1;
    EXPECT_EQ(greenIn(picture, x0, y0, x1, y1), 0) << "the ring stands outside the pixel";
    EXPECT_GT(greenIn(picture, x0 - 12, y0, x0 - 1, y1), 0) << "left side";
    EXPECT_GT(greenIn(picture, x1 + 1, y0, x1 + 12, y1), 0) << "right side";
    EXPECT_GT(greenIn(picture, x0, y1 + 1, x1, y1 + 12), 0) << "above";
    EXPECT_GT(greenIn(picture, x0, y0 - 12, x1, y0 - 1), 0) << "below";
    // The larger cluster's ring, on its left.
    EXPECT_GT(greenIn(picture, 10 * scale - 12, 5 * scale, 10 * scale - 1, 7 * scale - 1), 0);
    // The label "#7" beside the ring of object 7, right of it.
    const int label = greenIn(picture, x1 + 13, y0 - 30, x1 + 60, y1 + 30);
    EXPECT_GT(label, 20) << "a label beside the ring";
    // Every error pixel stays magenta, whatever is drawn around it.
    const std::vector<uint8_t> magenta(kErrorColour, kErrorColour + 3);
    int marked = 0;
    for (uint32_t y = 0; y < h * scale; ++y) {
        for (uint32_t x = 0; x < w * scale; ++x) {
            const uint8_t* c = picture.rgba.data() + (size_t{y} * picture.width + x) * 4;
            marked += std::vector<uint8_t>(c, c + 3) == magenta;
        }
    }
    EXPECT_EQ(marked, static_cast<int>(7 * scale * scale));
    // With names, the label says the name too: a longer label.
    std::vector<std::string> names(8);
    names[7] = "statue";
    const LabelledPicture named = labelledErrorPicture(frame, w, h, "async", &names);
    EXPECT_GT(greenIn(named, 0, 0, w * scale - 1, h * scale - 1),
              greenIn(picture, 0, 0, w * scale - 1, h * scale - 1) + 20);
}

}  // namespace
}  // namespace occsim
