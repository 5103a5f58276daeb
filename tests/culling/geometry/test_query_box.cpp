// The query box as a device draws it, and the near-plane rule on it (culling/geometry/
// query_box.h): the pad is bounded, the rule sees the pad, and no culler queries a box the rule
// refuses, however far its nodes reach.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "culling_fixtures.h"
#include "occsim/culling/geometry/query_box.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

using testing::buildTree;
using testing::makeFrame;
using testing::makeView;
using testing::randomBoxes;

TEST(QueryBoxPad, TheSizeTermStopsAtOneCentimetre) {
    const glm::dvec3 eye(0.0);
    for (const double size : {1e3, 1e6, 1e9, 1e12}) {
        const glm::dvec3 lo(-0.5 * size, 10, -0.5 * size), hi(0.5 * size, 11, 0.5 * size);
        const double distance_term = 1e-6 * glm::length(0.5 * (lo + hi) - eye);
        EXPECT_LE(queryBoxPad(lo, hi, eye) - distance_term, 0.01 + 1e-12) << size;
    }
    // Small boxes keep the pad they had: 10^-4 m at least, so a point still rasterises.
    EXPECT_NEAR(queryBoxPad({5, 0, 0}, {5, 0, 0}, {5, 0, 0}), 1e-4, 1e-12);
}

TEST(QueryBoxPad, GrowsWithTheDistanceFromTheEye) {
    const glm::dvec3 lo(0, 0, 0), hi(1, 1, 1);
    EXPECT_NEAR(queryBoxPad(lo, hi, {0.5, 0.5, 1000.5}) - queryBoxPad(lo, hi, {0.5, 0.5, 0.5}),
                1e-3, 1e-9);
}

// A box 10 km wide and the eye 5 mm above its top face, closer than the pad of that box: the box
// as drawn contains the eye. The rule on the box as given (what it was) let it be queried.
TEST(NearPlaneRule, TheEyeInsideThePadOfABoxTouchesIt) {
    const Aabb box{{0, 0, 0}, {1e4f, 1, 1}};
    const glm::vec3 eye(5000, 1.005f, 0.5f);
    const double pad = queryBoxPad(glm::dvec3(box.min), glm::dvec3(box.max), glm::dvec3(eye));
    ASSERT_GT(pad, 0.005);
    EXPECT_EQ(distanceToDrawnQueryBox(box, glm::dvec3(eye)), 0.0);
    EXPECT_TRUE(nearPlaneTouchesBox(box, eye, 0.001f));
    // Far enough that the drawn box stays beyond the near plane's reach: queried.
    EXPECT_FALSE(nearPlaneTouchesBox(box, {5000, 2.0f, 0.5f}, 0.5f));
    EXPECT_TRUE(nearPlaneTouchesBox(box, {5000, 1.2f, 0.5f}, 0.5f));
}

TEST(NearPlaneRule, UnknownPositionsTouchAndFarBoxesAtTheEdgeOfFloatDoNot) {
    Aabb nan_box{{0, 0, 0}, {1, 1, 1}};
    nan_box.max.x = std::nanf("");
    EXPECT_TRUE(nearPlaneTouchesBox(nan_box, {100, 0, 0}, 0.1f));
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_TRUE(nearPlaneTouchesBox(Aabb{glm::vec3(-inf), glm::vec3(inf)}, {5, 5, 5}, 0.1f));
    EXPECT_FALSE(nearPlaneTouchesBox(Aabb{{3e38f, 0, 0}, {3.1e38f, 1, 1}}, {0, 0, 0}, 0.1f));
    // A node from the eye's neighbourhood to the edge of float: its pad swallows the eye.
    EXPECT_TRUE(nearPlaneTouchesBox(Aabb{{-10, 0, -60}, {3e38f, 4, -20}}, {0, 2, 6}, 0.25f));
}

// Thirty boxes around the eye and one far along x (10^6, 10^9, 10^12 m, and the edge of float):
// every culler that decides for itself, with the script calling every query "hidden", never
// queries a box the rule refuses: not a node, not a multiquery's part, not an object.
TEST(NearPlaneRule, NoCullerQueriesABoxTheRuleRefusesHoweverFarItsNodesReach) {
    for (const float far_x : {1e6f, 1e9f, 1e12f, 3e38f}) {
        std::vector<Aabb> boxes = randomBoxes(30, 11, 12.0f);
        for (Aabb& b : boxes) b.min.z -= 30.0f, b.max.z -= 30.0f;  // all in z < 0
        boxes.push_back({{far_x, 0, -31}, {far_x, 1, -30}});
        const CullView view = makeView({0, 2, 6}, {0, 1.5f, -20}, 60.0f, 0.2f, 200.0f);
        const std::vector<uint8_t> hidden(boxes.size(), 0);
        for (const CullerRow* a : cullerRows()) {
            if (a->oracle) continue;
            const BspTree tree = buildTree(boxes);
            const auto culler = makeCuller(*a, CullerOptions{});
            culler->reset(tree);
            ScriptedQueryDevice device(2);
            for (uint32_t f = 0; f < 4; ++f) {
                device.setVisibility(hidden, boxes);
                device.clearLog();
                culler->cullAndRender(tree, makeFrame(view, f, f / 30.0), device);
                for (const Aabb& q : device.queriedBoxes()) {
                    EXPECT_FALSE(nearPlaneTouchesBox(q, view.eye, view.near_radius))
                        << a->name << " at " << far_x << ", frame " << f << ": queried a box "
                        << "whose drawn form reaches the near plane";
                }
            }
        }
    }
}

}  // namespace
}  // namespace occsim
