// The conditional-rendering culler (culling/cullers/conditional_culler.h) on the CPU test devices,
// which evaluate a condition as a GPU does: no OpenGL. The capability on each device is tested in
// that device's test file, the GL device's in tests/render/test_gl_query_device.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "culling/cullers/conditional_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/devices/approximate_device.h"
#include "occsim/culling/devices/tracing_device.h"
#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/depth_raster_device.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

using testing::buildTree;
using testing::makeFrame;

struct Camera {
    CullView view;
    glm::mat4 view_projection;
};

Camera cameraAt(glm::vec3 eye, glm::vec3 target) {
    constexpr float kFov = 60.0f, kNear = 0.1f, kFar = 1000.0f, kAspect = 4.0f / 3.0f;
    Camera c;
    c.view = testing::makeView(eye, target, kFov, kNear, kFar, kAspect);
    c.view_projection = glm::perspective(glm::radians(kFov), kAspect, kNear, kFar) *
                        glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    return c;
}

// A wall of boxes near the camera and a field of small boxes behind it that the wall hides from
// the cameras below, with a gap in the wall through which some of the field shows.
struct WallAndField {
    std::vector<Aabb> boxes;
    WallAndField() {
        for (int i = 0; i < 16; ++i) {
            if (i == 9) continue;  // the gap
            const float x = -24.0f + 3.0f * static_cast<float>(i);
            boxes.push_back({glm::vec3(x, 0, -1), glm::vec3(x + 3.0f, 12, 0)});
        }
        for (int z = 0; z < 16; ++z) {
            for (int x = 0; x < 16; ++x) {
                const glm::vec3 lo(-24.0f + 3.0f * static_cast<float>(x), 0.0f,
                                   -6.0f - 3.0f * static_cast<float>(z));
                boxes.push_back({lo, lo + glm::vec3(1.0f, 1.5f, 1.0f)});
            }
        }
    }
};

Camera frameCamera(uint64_t f) {
    return cameraAt({0.1f * static_cast<float>(f) - 3.0f, 3.0f, 12.0f}, {0.0f, 2.0f, -40.0f});
}

ConditionalOptions optionsOf(bool wait, bool node_queries, uint32_t ahead) {
    ConditionalOptions o;
    o.wait = wait;
    o.node_queries = node_queries;
    o.queries_ahead = ahead;
    return o;
}

// What one frame on the depth raster did: visible objects not drawn (by ground truth, every
// object in the frustum drawn), and hidden objects the device skipped.
struct RasterFrame {
    uint64_t missed = 0;
    uint64_t skipped = 0;
    uint64_t visible = 0;
};

RasterFrame runRasterFrame(Culler& culler, const BspTree& tree, DepthRasterDevice& device,
                           const std::vector<Aabb>& boxes, uint64_t f) {
    const Camera cam = frameCamera(f);
    device.beginFrame(cam.view_projection, cam.view.eye, boxes);
    culler.cullAndRender(tree, makeFrame(cam.view, f, static_cast<double>(f) / 30.0), device);
    const std::vector<uint8_t> truth = device.groundTruth();
    std::vector<uint8_t> drawn(boxes.size(), 0);
    for (uint32_t o : device.drawnObjects()) drawn[o] = 1;
    RasterFrame out;
    out.skipped = device.skippedObjects().size();
    for (uint32_t o = 0; o < boxes.size(); ++o) {
        out.visible += truth[o];
        out.missed += truth[o] && !drawn[o];
    }
    return out;
}

// Every mode, both units, with answers at once and late: no visible object is ever left out, and
// with time for the answers (waiting, or enough queries ahead) the hidden field is skipped.
class ConditionalOnTheRaster
    : public ::testing::TestWithParam<std::tuple<bool, bool, uint32_t, uint32_t>> {};

TEST_P(ConditionalOnTheRaster, DrawsEveryVisibleObjectAndSkipsHiddenOnesOnceAnswersAreKnown) {
    const auto [wait, node_queries, ahead, latency] = GetParam();
    const WallAndField scene;
    const BspTree tree = buildTree(scene.boxes, 4, BspSplitRule::Sah);
    ConditionalCuller culler(optionsOf(wait, node_queries, ahead));
    culler.reset(tree);
    DepthRasterDevice device(64, 48, latency);
    uint64_t skipped = 0;
    for (uint64_t f = 0; f < 30; ++f) {
        const RasterFrame r = runRasterFrame(culler, tree, device, scene.boxes, f);
        ASSERT_GT(r.visible, 0u);
        EXPECT_EQ(r.missed, 0u) << "frame " << f;
        EXPECT_EQ(device.pendingQueries(), 0u) << "every query released by the end of the frame";
        EXPECT_EQ(device.counters().results_fetched, 0u) << "nothing is read back";
        skipped += r.skipped;
        device.resetCounters();
    }
    // An answer is ready once more than `latency` commands followed its query's issue, the query
    // itself included; each item ahead adds at least one query and one draw.
    const bool answers_known = wait || 1 + 2 * ahead > latency;
    if (answers_known) {
        EXPECT_GT(skipped, 30u * 100u) << "the field behind the wall is skipped";
    } else {
        EXPECT_EQ(skipped, 0u) << "NoWait draws while the answer is not ready";
    }
}

INSTANTIATE_TEST_SUITE_P(WaitUnitsAheadLatency, ConditionalOnTheRaster,
                         ::testing::Combine(::testing::Bool(), ::testing::Bool(),
                                            ::testing::Values(0u, 16u), ::testing::Values(0u, 8u)));

// Every object in the frustum is queried (alone, or with its node's) and submitted exactly once.
TEST(ConditionalCuller, QueriesEachObjectInTheFrustumOnceAndDrawsEachOnce) {
    const WallAndField scene;
    const BspTree tree = buildTree(scene.boxes, 4, BspSplitRule::Sah);
    const Camera cam = frameCamera(0);
    const std::set<uint32_t> in_frustum = testing::inFrustum(scene.boxes, cam.view.frustum);
    for (bool node_queries : {false, true}) {
        ConditionalCuller culler(optionsOf(true, node_queries, 4));
        culler.reset(tree);
        ScriptedQueryDevice device;
        device.setVisibility(std::vector<uint8_t>(scene.boxes.size(), 1), scene.boxes);
        culler.cullAndRender(tree, makeFrame(cam.view, 0, 0.0), device);
        std::vector<uint32_t> drawn = device.drawnObjects();
        std::sort(drawn.begin(), drawn.end());
        EXPECT_EQ(std::set<uint32_t>(drawn.begin(), drawn.end()), in_frustum);
        EXPECT_EQ(drawn.size(), in_frustum.size()) << "no object drawn twice";
        EXPECT_EQ(device.counters().conditional_draws, in_frustum.size());
        if (node_queries) {
            EXPECT_LT(device.counters().queries_issued, in_frustum.size() / 2);
            for (const QueryTag& tag : device.queryTags())
                EXPECT_NE(tag.subject, QueryTag::Subject::Object);
        } else {
            EXPECT_EQ(device.counters().queries_issued, in_frustum.size());
            for (const QueryTag& tag : device.queryTags())
                EXPECT_EQ(tag.subject, QueryTag::Subject::Object);
        }
    }
}

TEST(ConditionalCuller, DrawsAnObjectTheNearPlaneMayCutUnconditionallyWithoutAQuery) {
    // The eye inside object 0's box; object 1 ahead of it.
    const std::vector<Aabb> boxes = {{glm::vec3(-1, -1, -1), glm::vec3(1, 1, 1)},
                                     {glm::vec3(-1, -1, -20), glm::vec3(1, 1, -18)}};
    const BspTree tree = buildTree(boxes, 1);
    const Camera cam = cameraAt({0, 0, 0}, {0, 0, -10});
    for (bool node_queries : {false, true}) {
        ConditionalCuller culler(optionsOf(true, node_queries, 0));
        culler.reset(tree);
        ScriptedQueryDevice device;
        device.setVisibility({0, 0}, boxes);  // whatever the answers say
        culler.cullAndRender(tree, makeFrame(cam.view, 0, 0.0), device);
        EXPECT_EQ(device.drawnObjects(), (std::vector<uint32_t>{0})) << "drawn unconditionally";
        EXPECT_EQ(device.skippedObjects(), (std::vector<uint32_t>{1})) << "occluded: skipped";
        EXPECT_EQ(device.counters().queries_issued, 1u) << "no query on the box at the eye";
        EXPECT_EQ(device.counters().conditional_draws, 1u);
    }
}

TEST(ConditionalCuller, DecidesTheSameInEveryRun) {
    const WallAndField scene;
    const BspTree tree = buildTree(scene.boxes, 4, BspSplitRule::Sah);
    auto run = [&] {
        ConditionalCuller culler(optionsOf(false, false, 3));
        culler.reset(tree);
        DepthRasterDevice device(64, 48, 5);
        std::vector<std::vector<uint32_t>> log;
        for (uint64_t f = 0; f < 10; ++f) {
            runRasterFrame(culler, tree, device, scene.boxes, f);
            log.push_back(device.drawnObjects());
            log.push_back(device.skippedObjects());
        }
        return log;
    };
    EXPECT_EQ(run(), run());
}

TEST(ConditionalCuller, OnADeviceWithoutTheCapabilityThrowsBeforeAnyWork) {
    const std::vector<Aabb> boxes = {{glm::vec3(-1, -1, -11), glm::vec3(1, 1, -9)}};
    const BspTree tree = buildTree(boxes, 1);
    ScriptedQueryDevice device;
    device.setVisibility({1}, boxes);
    device.offerConditionalRendering(false);
    ConditionalCuller culler;
    culler.reset(tree);
    EXPECT_THROW(
        culler.cullAndRender(tree, makeFrame(cameraAt({0, 0, 0}, {0, 0, -10}).view, 0, 0), device),
        std::logic_error);
    EXPECT_TRUE(device.drawnObjects().empty());
    EXPECT_EQ(device.counters().queries_issued, 0u);
}

// --- The registry row and the refusal ------------------------------------------------------------

TEST(ConditionalRegistration, NeedsConditionalRenderingAndIsConservativeWithoutQueryKnobs) {
    const CullerRow* t = findCuller("conditional");
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t->device_needs, uint32_t{kConditionalRendering});
    EXPECT_TRUE(t->conservative);
    EXPECT_FALSE(t->issues_queries) << "no answer reaches it: threshold and stale cannot apply";
    // After the other query cullers, before the oracle (hzb and masked between them).
    const std::vector<std::string> names = cullerNames();
    const auto at = [&](const std::string& n) {
        return std::find(names.begin(), names.end(), n) - names.begin();
    };
    EXPECT_LT(at("async"), at("conditional"));
    EXPECT_LT(at("conditional"), at("ideal"));
}

TEST(ConditionalRegistration, OptionsOutOfRangeOrOfTheWrongTypeGetTheBuiltInsMessage) {
    const CullerRow& t = *findCuller("conditional");
    OptionValues values(t.options);
    EXPECT_EQ(checkOptionValues(t, values), "");
    values.set("queries_ahead", 70000);
    EXPECT_EQ(checkOptionValues(t, values),
              "queries_ahead: expected an integer in [0, 65536] (queries), got 70000");
    values.set("queries_ahead", 2.5);
    EXPECT_EQ(checkOptionValues(t, values),
              "queries_ahead: expected an integer in [0, 65536] (queries), got 2.5");
    values.set("queries_ahead", 16);
    values.set("wait", 2);
    EXPECT_EQ(checkOptionValues(t, values), "wait: expected true or false, got 2");
}

}  // namespace
}  // namespace occsim
