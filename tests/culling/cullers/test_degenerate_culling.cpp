// Culling on degenerate input and at the edges of the query contract (issue "Accurate under
// stress"): a box with a NaN coordinate, zero-extent boxes, everything at one point, one object,
// no object, the eye inside a box; and device decorators that must keep results ready in issue
// order. All on the scripted device, every registered culler that decides without ground truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "culling_fixtures.h"
#include "occsim/culling/devices/approximate_device.h"
#include "occsim/culling/devices/tracing_device.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

using testing::buildTree;
using testing::makeFrame;
using testing::makeView;
using testing::randomBoxes;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

std::vector<const CullerRow*> decidingCullers() {
    std::vector<const CullerRow*> out;
    for (const CullerRow* a : cullerRows()) {
        if (!a->oracle) out.push_back(a);
    }
    return out;
}

// Runs `frames` frames of a static view and returns the objects drawn in each.
std::vector<std::set<uint32_t>> run(const CullerRow& algorithm, const std::vector<Aabb>& boxes,
                                    const std::vector<uint8_t>& visible, const CullView& view,
                                    uint32_t latency, uint32_t frames) {
    const BspTree tree = buildTree(boxes);
    const auto culler = makeCuller(algorithm, CullerOptions{});
    culler->reset(tree);
    ScriptedQueryDevice device(latency);
    std::vector<std::set<uint32_t>> drawn;
    for (uint32_t f = 0; f < frames; ++f) {
        device.setVisibility(visible, boxes);
        device.clearLog();
        culler->cullAndRender(tree, makeFrame(view, f, f / 30.0), device);
        drawn.emplace_back(device.drawnObjects().begin(), device.drawnObjects().end());
    }
    return drawn;
}

// An object whose box has a NaN coordinate: no test can say where it is, so no culler may skip
// it, and none may query it (a query on such a box rasterises nothing and would say "hidden").
TEST(DegenerateBoxes, AnObjectWithANaNCoordinateIsDrawnEveryFrameByEveryCuller) {
    std::vector<Aabb> boxes = randomBoxes(300, 5, 40.0f);
    const uint32_t nan_object = 17;
    boxes[nan_object].min.y = kNaN;
    const std::vector<uint8_t> visible(boxes.size(), 1);
    const CullView view = makeView({0, 5, 60}, {0, 0, 0});
    for (const CullerRow* a : decidingCullers()) {
        for (uint32_t latency : {0u, 3u, 50u}) {
            const auto drawn = run(*a, boxes, visible, view, latency, 8);
            for (size_t f = 0; f < drawn.size(); ++f) {
                EXPECT_TRUE(drawn[f].count(nan_object))
                    << a->name << " latency " << latency << " frame " << f;
            }
        }
    }
}

TEST(DegenerateBoxes, NearPlaneRuleTreatsUnknownPositionsAsTouching) {
    Aabb nan_box{{0, 0, 0}, {1, 1, 1}};
    nan_box.max.x = kNaN;
    EXPECT_TRUE(nearPlaneTouchesBox(nan_box, {100, 0, 0}, 0.1f));
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_TRUE(nearPlaneTouchesBox(Aabb{glm::vec3(-inf), glm::vec3(inf)}, {5, 5, 5}, 0.1f));
    EXPECT_FALSE(nearPlaneTouchesBox(Aabb{{0, 0, 0}, {1, 1, 1}}, {100, 0, 0}, 0.1f));
}

// Conservative cullers draw every object the scripted visibility calls visible, whatever the
// shape of the scene.
void expectDrawsEveryVisible(const std::vector<Aabb>& boxes, const CullView& view,
                             const std::string& what) {
    const std::vector<uint8_t> visible(boxes.size(), 1);
    for (const CullerRow* a : decidingCullers()) {
        if (!a->conservative) continue;
        for (uint32_t latency : {0u, 4u}) {
            const auto drawn = run(*a, boxes, visible, view, latency, 5);
            for (size_t f = 0; f < drawn.size(); ++f) {
                for (uint32_t o = 0; o < boxes.size(); ++o) {
                    if (classify(view.frustum, boxes[o]) == FrustumTest::Outside) continue;
                    EXPECT_TRUE(drawn[f].count(o)) << what << ": " << a->name << " latency "
                                                   << latency << " frame " << f << " object " << o;
                }
            }
        }
    }
}

TEST(DegenerateScenes, ZeroExtentBoxesAreDrawn) {
    std::vector<Aabb> boxes;
    for (int i = 0; i < 40; ++i) {
        const glm::vec3 p(static_cast<float>(i % 8) * 2.0f, 0.0f,
                          -static_cast<float>(i / 8) * 3.0f);
        boxes.push_back({p, p});  // points
    }
    expectDrawsEveryVisible(boxes, makeView({7, 2, 10}, {7, 0, -6}), "points");
}

TEST(DegenerateScenes, EveryObjectAtOnePointIsDrawn) {
    const std::vector<Aabb> boxes(64, Aabb{{1, 1, -5}, {2, 2, -4}});
    expectDrawsEveryVisible(boxes, makeView({0, 0, 5}, {1, 1, -5}), "one point");
}

TEST(DegenerateScenes, OneObjectAndNoObjectWork) {
    expectDrawsEveryVisible({Aabb{{-1, -1, -6}, {1, 1, -4}}}, makeView({0, 0, 5}, {0, 0, -5}),
                            "one");
    expectDrawsEveryVisible({}, makeView({0, 0, 5}, {0, 0, -5}), "none");
}

// The eye inside an object's box, and the near plane cutting another: such boxes are never
// queried (a clipped query could report zero samples for a visible box), always drawn.
TEST(DegenerateScenes, BoxesAroundTheEyeOrCutByTheNearPlaneAreDrawnNotQueried) {
    std::vector<Aabb> boxes = randomBoxes(200, 9, 30.0f);
    const glm::vec3 eye(3, 1, 3);
    boxes.push_back({eye - glm::vec3(2), eye + glm::vec3(2)});  // around the eye
    boxes.push_back({eye + glm::vec3(-1, -1, -0.15f), eye + glm::vec3(1, 1, -0.05f)});  // cut
    const CullView view = makeView(eye, eye + glm::vec3(0, 0, -10), 60.0f, 0.1f);
    std::vector<uint8_t> visible(boxes.size(), 0);  // the script would call every query "hidden"
    for (const CullerRow* a : decidingCullers()) {
        const BspTree tree = buildTree(boxes);
        const auto culler = makeCuller(*a, CullerOptions{});
        culler->reset(tree);
        ScriptedQueryDevice device(2);
        for (uint32_t f = 0; f < 4; ++f) {
            device.setVisibility(visible, boxes);
            device.clearLog();
            culler->cullAndRender(tree, makeFrame(view, f, f / 30.0), device);
            const auto& drawn = device.drawnObjects();
            for (uint32_t o : {200u, 201u}) {
                EXPECT_NE(std::find(drawn.begin(), drawn.end(), o), drawn.end())
                    << a->name << " frame " << f << " object " << o;
                for (const Aabb& q : device.queriedBoxes()) {
                    EXPECT_FALSE(q.min == boxes[o].min && q.max == boxes[o].max)
                        << a->name << " queried object " << o;
                }
            }
        }
    }
}

// ---- The query contract through the decorators ----------------------------------------------

// Issues and polls at random; at every step, a ready query means every earlier one still open is
// ready too (results become ready in issue order), and fetching in issue order never disagrees.
void expectReadyInIssueOrder(RenderDevice& device, const std::vector<Aabb>& boxes,
                             const std::string& what) {
    std::mt19937 rng(3);
    std::vector<QueryId> open;
    for (int step = 0; step < 400; ++step) {
        const int action = static_cast<int>(rng() % 4);
        if (action < 2 || open.empty()) {
            open.push_back(device.issueQuery(boxes[rng() % boxes.size()]));
        } else if (action == 2) {
            device.takeAnswer(open.front());
            open.erase(open.begin());
        } else {
            device.drawObject(static_cast<uint32_t>(rng() % boxes.size()));
        }
        bool later_ready_seen = false;
        for (size_t i = open.size(); i-- > 0;) {
            const bool ready = device.isQueryReady(open[i]);
            if (later_ready_seen) {
                EXPECT_TRUE(ready) << what << ": step " << step << ", query " << i
                                   << " of the open ones is not ready but a later one is";
            }
            later_ready_seen |= ready;
        }
    }
}

TEST(QueryContract, DevicesAndDecoratorsKeepResultsReadyInIssueOrder) {
    const std::vector<Aabb> boxes = randomBoxes(20, 2, 10.0f);
    std::vector<uint8_t> visible(boxes.size(), 0);
    for (size_t i = 0; i < visible.size(); i += 3) visible[i] = 1;
    for (uint32_t latency : {0u, 3u, 9u}) {
        ScriptedQueryDevice plain(latency);
        plain.setVisibility(visible, boxes);
        expectReadyInIssueOrder(plain, boxes, "scripted");

        ScriptedQueryDevice inner(latency);
        inner.setVisibility(visible, boxes);
        ApproximateDevice threshold(inner, {2, false});
        expectReadyInIssueOrder(threshold, boxes, "threshold");

        ScriptedQueryDevice inner2(latency);
        inner2.setVisibility(visible, boxes);
        ApproximateDevice stale(inner2, {0, true});
        expectReadyInIssueOrder(stale, boxes, "stale results");

        ScriptedQueryDevice inner3(latency);
        inner3.setVisibility(visible, boxes);
        TracingDevice tracer(inner3);
        tracer.beginTrace(0);
        expectReadyInIssueOrder(tracer, boxes, "tracing");
    }
}

}  // namespace
}  // namespace occsim
