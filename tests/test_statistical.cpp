// The statistical culler (Kovalcik & Sochor 2005) on test devices whose answers depend on what was
// drawn before them (culling/depth_raster_device.h): no OpenGL.
#include "culling/depth_raster_device.h"
#include "culling/scripted_query_device.h"
#include "culling/statistical_culler.h"
#include "culling_fixtures.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <vector>

namespace occsim {
namespace {

using testing::buildTree;
using testing::makeFrame;

struct Camera {
    CullView view;
    glm::mat4 view_projection;
};

Camera makeCamera(glm::vec3 eye, glm::vec3 target, float fov_deg = 60.0f, float near = 0.1f,
                  float far = 1000.0f, float aspect = 4.0f / 3.0f) {
    Camera c;
    c.view = testing::makeView(eye, target, fov_deg, near, far, aspect);
    c.view_projection = glm::perspective(glm::radians(fov_deg), aspect, near, far) *
                        glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    return c;
}

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

TEST(DepthRasterDevice, ANearerDrawnBoxHidesAFartherOne) {
    const Camera cam = makeCamera({0, 1, 10}, {0, 1, 0});
    DepthRasterDevice device(32, 24);
    const std::vector<Aabb> boxes = {{glm::vec3(-5, -5, -1), glm::vec3(5, 5, 0)},
                                     {glm::vec3(-1, 0, -20), glm::vec3(1, 2, -18)}};
    device.beginFrame(cam.view_projection, cam.view.eye, boxes);
    EXPECT_GT(device.queryResult(device.issueQuery(boxes[1])), 0u) << "nothing drawn yet";
    device.drawObject(0);
    EXPECT_EQ(device.queryResult(device.issueQuery(boxes[1])), 0u) << "behind the drawn wall";
    EXPECT_GT(device.queryResult(device.issueQuery(boxes[0])), 0u) << "ties pass";
    // A box containing a hidden object and part of the wall passes; ground truth sees the wall.
    Aabb both = boxes[0];
    extend(both, boxes[1]);
    EXPECT_GT(device.queryResult(device.issueQuery(both)), 0u);
    EXPECT_EQ(device.groundTruth(), (std::vector<uint8_t>{1, 0}));
}

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
    culler.cullAndRender(tree, makeFrame(cam.view, frame, static_cast<double>(frame) / 30.0), device);
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
        const Camera cam =
            makeCamera({0.2f * static_cast<float>(f) - 6.0f, 3, 12}, {0, 2, -40});
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

}  // namespace
}  // namespace occsim
