// The OpenGL backend through a real headless context, on every backend the build has (EGL, and
// OSMesa where configured): object IDs, reverse-Z depth, and occlusion queries that are
// conservative and asynchronous. Then the backend choice itself: what a context must offer, and
// the one-line reasons when a backend or device cannot serve.
#include <gtest/gtest.h>
#if OCCSIM_HAVE_OSMESA
// GL/osmesa.h brings GL/gl.h, which cannot stand beside the core-profile header the renderer
// uses: the two OSMesa calls the test needs, as osmesa.h declares them (an OSMesaContext is a
// pointer, a GLboolean an unsigned char).
extern "C" {
void* OSMesaGetCurrentContext();
unsigned char OSMesaGetColorBuffer(void* context, int* width, int* height, int* format,
                                   void** buffer);
}
#endif

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>

#include "headless_backends.h"
#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/geometry/frustum.h"
#include "render/gl_checked_call.h"
#include "render/gl_frame_timer.h"
#include "render/gl_query_device.h"
#include "render/gl_renderer.h"
#include "render/headless_context.h"
#include "render/osmesa_colour_buffer.h"
#include "render/png_writer.h"

namespace occsim {
namespace {

// A unit cube [-0.5, 0.5]^3 with per-face normals.
MeshData cubeMesh() {
    MeshData m;
    const glm::vec3 normals[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                  {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        const glm::vec3 u = glm::abs(n.x) > 0 ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 v = glm::cross(n, u);
        const auto base = static_cast<uint32_t>(m.positions.size());
        for (int k = 0; k < 4; ++k) {
            const float su = (k & 1) ? 0.5f : -0.5f, sv = (k & 2) ? 0.5f : -0.5f;
            m.positions.push_back(0.5f * n + su * u + sv * v);
            m.normals.push_back(n);
        }
        m.indices.insert(m.indices.end(), {base, base + 1, base + 3, base, base + 3, base + 2});
    }
    return m;
}

class RenderTest : public ::testing::TestWithParam<Backend> {
  protected:
    static constexpr uint32_t kW = 128, kH = 96;
    void SetUp() override {
        context_ = createHeadlessContext({GetParam(), {}}, kW, kH);
        renderer_ = std::make_unique<GlRenderer>(kW, kH);
        const MeshData cube = cubeMesh();
        renderer_->uploadMeshes(std::span<const MeshData>(&cube, 1));
        // Object 0: a wall 4 x 4 at z = -5; object 1: a small cube behind it at z = -20;
        // object 2: a small cube off to the side at z = -20, not hidden.
        renderer_->setObjectMeshes(std::vector<uint32_t>{0, 0, 0});
        world_ = {
            glm::translate(glm::dmat4(1.0), {0, 0, -5}) * glm::scale(glm::dmat4(1.0), {4, 4, 0.2}),
            glm::translate(glm::dmat4(1.0), {0, 0, -20}),
            glm::translate(glm::dmat4(1.0), {12, 0, -20})};
        boxes_ = {{{-2, -2, -5.1f}, {2, 2, -4.9f}},
                  {{-0.5f, -0.5f, -20.5f}, {0.5f, 0.5f, -19.5f}},
                  {{11.5f, -0.5f, -20.5f}, {12.5f, 0.5f, -19.5f}}};
        setEye({0, 0, 0});
    }
    void setEye(glm::dvec3 eye, float near_radius = 0.0f) {
        ViewSetup view;
        view.eye = eye;
        view.near_radius = near_radius;
        view.view_rotation = glm::mat4(1.0f);  // looking down -z
        view.projection = reverseZPerspective(glm::radians(90.0f), float(kW) / kH, 0.1f, 1000.0f);
        model_view_.clear();
        for (const glm::dmat4& w : world_) {
            model_view_.push_back(glm::mat4(glm::translate(glm::dmat4(1.0), -eye) * w));
        }
        renderer_->setView(view, model_view_);
    }
    std::unique_ptr<HeadlessContext> context_;
    std::unique_ptr<GlRenderer> renderer_;
    std::vector<glm::dmat4> world_;
    std::vector<glm::mat4> model_view_;
    std::vector<Aabb> boxes_;
};

TEST_P(RenderTest, ContextIsOpenGl45CoreOnTheBackendAskedFor) {
    EXPECT_NE(context_->rendererName().find("4.5"), std::string::npos) << context_->rendererName();
    const ContextInfo& info = context_->info();
    EXPECT_EQ(info.backend, GetParam());
    EXPECT_EQ(info.device.has_value(), GetParam() == Backend::Egl);
    EXPECT_FALSE(info.vendor.empty());
    EXPECT_FALSE(info.renderer.empty());
    EXPECT_FALSE(info.driver.empty());
    EXPECT_TRUE(info.fallback.empty());
}

TEST_P(RenderTest, ObjectIdBufferHoldsObjectIndexPlusOneAndZeroForBackground) {
    renderer_->beginFrame();
    renderer_->drawObject(0);
    renderer_->drawObject(2);
    renderer_->finish();
    std::vector<uint32_t> ids;
    renderer_->readObjectIds(ids);
    ASSERT_EQ(ids.size(), size_t{kW} * kH);
    EXPECT_EQ(ids[(kH / 2) * kW + kW / 2], 1u) << "the wall fills the centre";
    EXPECT_EQ(ids[0], 0u) << "a corner sees background";
    EXPECT_GT(std::count(ids.begin(), ids.end(), 3u), 0) << "the side cube is visible";
}

TEST_P(RenderTest, NearerObjectWinsWhateverTheDrawOrder) {
    // Reverse-Z with GL_GREATER: the wall (nearer) hides the cube behind it in either order.
    for (int order = 0; order < 2; ++order) {
        renderer_->beginFrame();
        renderer_->drawObject(order ? 0 : 1);
        renderer_->drawObject(order ? 1 : 0);
        std::vector<uint32_t> ids;
        renderer_->readObjectIds(ids);
        EXPECT_EQ(std::count(ids.begin(), ids.end(), 2u), 0) << "order " << order;
    }
}

TEST_P(RenderTest, QueryReportsZeroSamplesForABoxBehindAnOccluderAndSomeForAVisibleOne) {
    GlQueryDevice device(*renderer_, LatencyMode{});
    renderer_->beginFrame();
    device.drawObject(0);
    const QueryId hidden = device.issueQuery(boxes_[1]);
    const QueryId visible = device.issueQuery(boxes_[2]);
    EXPECT_FALSE(device.takeAnswer(hidden).visible);
    EXPECT_TRUE(device.takeAnswer(visible).visible);
    EXPECT_EQ(device.counters().queries_issued, 2u);
    EXPECT_EQ(device.counters().objects_drawn, 1u);
    EXPECT_EQ(device.counters().triangles_drawn, 12u);
}

TEST_P(RenderTest, QueryBoxesWriteNeitherColourNorDepth) {
    GlQueryDevice device(*renderer_, LatencyMode{});
    renderer_->beginFrame();
    device.takeAnswer(device.issueQuery(boxes_[0]));  // the wall's box, nothing drawn
    device.drawObject(1);                             // must still show: no depth was written
    std::vector<uint32_t> ids;
    renderer_->readObjectIds(ids);
    EXPECT_GT(std::count(ids.begin(), ids.end(), 2u), 0);
}

TEST_P(RenderTest, QueryOnABoxCoplanarWithTheOccluderFaceCountsAsVisible) {
    // The query box's front face lies exactly on the wall's front face: conservative means visible.
    GlQueryDevice device(*renderer_, LatencyMode{});
    renderer_->beginFrame();
    device.drawObject(0);
    const Aabb coplanar{{-1, -1, -6}, {1, 1, -4.9f}};
    EXPECT_TRUE(device.takeAnswer(device.issueQuery(coplanar)).visible);
}

// A wall that fills the view 5 m ahead, and a box 10 km across whose near face is 0.5 m ahead of
// the eye, in front of the wall: the box is visible. Its query box used to be drawn grown by 10^-4
// of its size (1.4 m), which put the eye inside it: only the far faces, behind the wall,
// rasterised, and the query said "hidden". The pad is bounded now (query_box.h).
TEST_P(RenderTest, QueryOnALargeBoxJustAheadOfTheEyeCountsAsVisible) {
    world_[0] =
        glm::translate(glm::dmat4(1.0), {0, 0, -5}) * glm::scale(glm::dmat4(1.0), {1e3, 1e3, 0.2});
    setEye({0, 0, 0});
    GlQueryDevice device(*renderer_, LatencyMode{});
    renderer_->beginFrame();
    device.drawObject(0);
    const Aabb large{{-5e3f, -5e3f, -1e4f}, {5e3f, 5e3f, -0.5f}};
    EXPECT_FALSE(renderer_->queryBoxNearEye(large));
    EXPECT_TRUE(device.takeAnswer(device.issueQuery(large)).visible);
}

// The device's own guard: a query whose box, as drawn, reaches the near plane (here it holds the
// eye, and every face it shows lies behind the wall) is answered "visible" whatever its samples,
// so a culler that skipped the rule (a plugin) still cannot lose what the box holds.
TEST_P(RenderTest, AQueryOnABoxAroundTheEyeIsAnsweredVisibleByTheDevice) {
    world_[0] =
        glm::translate(glm::dmat4(1.0), {0, 0, -5}) * glm::scale(glm::dmat4(1.0), {1e3, 1e3, 0.2});
    const float near_radius =
        static_cast<float>(nearPlaneCornerDistance(0.1, glm::radians(90.0), double(kW) / kH));
    setEye({0, 0, 0}, near_radius);
    GlQueryDevice device(*renderer_, LatencyMode{});
    renderer_->beginFrame();
    device.drawObject(0);
    const Aabb around{{-10, -10, -10}, {10, 10, 10}};
    ASSERT_TRUE(renderer_->queryBoxNearEye(around));
    const QueryAnswer answer = device.takeAnswer(device.issueQuery(around));
    EXPECT_EQ(answer.samples, 0u) << "every face it shows is behind the wall";
    EXPECT_TRUE(answer.visible);
}

TEST_P(RenderTest, DeterministicLatencyMakesResultsReadyOnlyAfterNLaterCommands) {
    GlQueryDevice device(*renderer_, LatencyMode{true, 3});
    renderer_->beginFrame();
    const QueryId q = device.issueQuery(boxes_[2]);
    for (int i = 0; i < 3; ++i) {
        EXPECT_FALSE(device.isQueryReady(q)) << i;
        device.drawObject(0);
    }
    EXPECT_TRUE(device.isQueryReady(q));
    const QueryAnswer answer = device.takeAnswer(q);
    EXPECT_TRUE(answer.visible);
    EXPECT_GT(answer.samples, 0u);
    EXPECT_FALSE(answer.waited);
    EXPECT_EQ(device.counters().results_waited, 0u);
}

TEST_P(RenderTest, FetchingAnUnreadyResultCountsAsAWait) {
    GlQueryDevice device(*renderer_, LatencyMode{true, 100});
    renderer_->beginFrame();
    const QueryId q = device.issueQuery(boxes_[2]);
    const QueryAnswer answer = device.takeAnswer(q);
    EXPECT_TRUE(answer.visible);
    EXPECT_TRUE(answer.waited);
    EXPECT_EQ(device.counters().results_waited, 1u);
}

// A second take of the same id is a bug in the caller. Debug builds abort with a message; every
// build leaves the pool alone: the id is not released twice, so two later queries never share
// one GL query object (they did when a double take pushed the id onto the free list twice).
TEST_P(RenderTest, TakingAnAnswerTwiceNeverReleasesItsIdTwice) {
    GlQueryDevice device(*renderer_, LatencyMode{});
    renderer_->beginFrame();
    const QueryId q = device.issueQuery(boxes_[2]);
    device.takeAnswer(q);
#ifdef NDEBUG
    const QueryAnswer again = device.takeAnswer(q);
    EXPECT_TRUE(again.visible) << "the safe answer";
    EXPECT_EQ(device.queriesInFlight(), 0u);
    const QueryId a = device.issueQuery(boxes_[2]);
    const QueryId b = device.issueQuery(boxes_[1]);
    EXPECT_NE(a, b);
    EXPECT_EQ(device.queriesInFlight(), 2u);
    device.takeAnswer(a);
    device.takeAnswer(b);
#else
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(device.takeAnswer(q), "GlQueryDevice::takeAnswer: query id 0 is not in flight");
#endif
}

// The debug builds' checked calls on the query path report a GL error with the call's text.
TEST_P(RenderTest, AGlErrorOnTheQueryPathIsReportedWithTheCallsName) {
    EXPECT_EQ(glErrorAfter("glFlush()"), "") << "no error pending";
    glEndQuery(GL_SAMPLES_PASSED);  // no query begun: GL_INVALID_OPERATION
    EXPECT_EQ(glErrorAfter("glEndQuery(GL_SAMPLES_PASSED)"),
              "glEndQuery(GL_SAMPLES_PASSED): GL_INVALID_OPERATION (0x502)");
    EXPECT_EQ(glErrorAfter("glFlush()"), "") << "the reported error is cleared";
}

// Latency as the culler feels it: the commands submitted after a query by the time the device
// knew its answer was ready, once per answer, whether it was polled ready or waited for.
TEST_P(RenderTest, AnswerLatencyCountsTheCommandsAfterAQueryUntilItsAnswerWasReady) {
    GlQueryDevice device(*renderer_, LatencyMode{true, 3});
    renderer_->beginFrame();
    const QueryId polled = device.issueQuery(boxes_[2]);
    const QueryId waited = device.issueQuery(boxes_[1]);  // one command after `polled`
    for (int i = 0; i < 3; ++i) device.drawObject(0);
    EXPECT_TRUE(device.isQueryReady(polled));  // 4 commands after it
    EXPECT_TRUE(device.isQueryReady(polled));  // asked again: the same answer, counted once
    device.takeAnswer(polled);
    device.takeAnswer(waited);  // 3 after it: not ready, waited for
    std::vector<uint32_t> latencies;
    device.takeAnswerLatencies(latencies);
    EXPECT_EQ(latencies, (std::vector<uint32_t>{4, 3}));
    device.takeAnswerLatencies(latencies);
    EXPECT_TRUE(latencies.empty());
}

TEST_P(RenderTest, MeasuredModeRecordsEveryFetchedAnswerOnce) {
    GlQueryDevice device(*renderer_, LatencyMode{});
    renderer_->beginFrame();
    std::vector<QueryId> ids;
    for (int i = 0; i < 5; ++i) {
        ids.push_back(device.issueQuery(boxes_[2]));
        device.drawObject(0);
    }
    for (QueryId id : ids) device.takeAnswer(id);
    std::vector<uint32_t> latencies;
    device.takeAnswerLatencies(latencies);
    ASSERT_EQ(latencies.size(), 5u);
    // The first query had 9 commands after it when the last was submitted: no answer can have
    // been known later than that.
    for (size_t i = 0; i < latencies.size(); ++i) EXPECT_LE(latencies[i], 9u - 2 * i) << i;
}

// The timer query brackets a frame and its result is there after glFinish. Its value is only
// checked to be a number: on llvmpipe it does not time rasterisation.
TEST_P(RenderTest, TheFrameTimerGivesAResultAfterFinish) {
    GlFrameTimer timer;
    for (int frame = 0; frame < 2; ++frame) {
        timer.begin();
        renderer_->beginFrame();
        renderer_->drawObject(0);
        timer.end();
        renderer_->finish();
        const double ms = timer.resultMs();
        EXPECT_GE(ms, 0.0);
        EXPECT_TRUE(std::isfinite(ms));
    }
}

TEST_P(RenderTest, ManyQueriesInFlightResolveInOrderAndIdsAreReused) {
    GlQueryDevice device(*renderer_, LatencyMode{});
    renderer_->beginFrame();
    device.drawObject(0);
    std::vector<QueryId> ids;
    for (int i = 0; i < 50; ++i) ids.push_back(device.issueQuery(boxes_[i % 2 ? 2 : 1]));
    EXPECT_EQ(device.queriesInFlight(), 50u);
    for (int i = 0; i < 50; ++i) EXPECT_EQ(device.takeAnswer(ids[i]).visible, i % 2 == 1) << i;
    EXPECT_EQ(device.queriesInFlight(), 0u);
    const QueryId again = device.issueQuery(boxes_[2]);
    EXPECT_LT(again, 50u) << "a released query object is reused";
    device.takeAnswer(again);
}

TEST_P(RenderTest, CameraFarFromTheOriginRendersTheSameImage) {
    // Camera-relative rendering: the same scene shifted by 10^6 m renders identically.
    renderer_->beginFrame();
    renderer_->drawObject(0);
    renderer_->drawObject(2);
    std::vector<uint32_t> near_origin;
    renderer_->readObjectIds(near_origin);
    const glm::dvec3 shift(1e6, -2e6, 3e6);
    for (glm::dmat4& w : world_) w = glm::translate(glm::dmat4(1.0), shift) * w;
    setEye(shift);
    renderer_->beginFrame();
    renderer_->drawObject(0);
    renderer_->drawObject(2);
    std::vector<uint32_t> far_away;
    renderer_->readObjectIds(far_away);
    EXPECT_EQ(near_origin, far_away);
}

// The basis of the tie tolerance (docs/error.md): a drawn object stores the same depth at a pixel
// whatever else was drawn before it, so ground truth and a culled frame agree on it exactly.
TEST_P(RenderTest, ADrawnObjectStoresTheSameDepthWhateverElseIsDrawn) {
    renderer_->beginFrame();
    renderer_->drawObject(0);
    std::vector<uint32_t> alone, ids_alone;
    renderer_->readDepthRanks(alone);
    renderer_->readObjectIds(ids_alone);
    renderer_->beginFrame();
    renderer_->drawObject(2);
    renderer_->drawObject(1);
    renderer_->drawObject(0);
    std::vector<uint32_t> after_others, ids_after;
    renderer_->readDepthRanks(after_others);
    renderer_->readObjectIds(ids_after);
    size_t wall = 0;
    for (size_t i = 0; i < alone.size(); ++i) {
        if (ids_alone[i] != 1) continue;
        ++wall;
        ASSERT_EQ(ids_after[i], 1u) << i;
        EXPECT_EQ(alone[i], after_others[i]) << "pixel " << i;
    }
    EXPECT_GT(wall, 100u);
}

TEST_P(RenderTest, DepthRanksAreZeroForBackgroundAndLargerForNearerSurfaces) {
    renderer_->beginFrame();
    renderer_->drawObject(0);  // the wall at 5 m
    renderer_->drawObject(2);  // the cube at 20 m, off to the side
    std::vector<uint32_t> ranks, ids;
    renderer_->readDepthRanks(ranks);
    renderer_->readObjectIds(ids);
    uint32_t wall_min = UINT32_MAX, cube_max = 0;
    size_t background = 0;
    for (size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] == 0) {
            EXPECT_EQ(ranks[i], 0u);
            ++background;
        }
        if (ids[i] == 1) wall_min = std::min(wall_min, ranks[i]);
        if (ids[i] == 3) cube_max = std::max(cube_max, ranks[i]);
    }
    EXPECT_GT(background, 0u);
    ASSERT_GT(cube_max, 0u);
    EXPECT_GT(wall_min, cube_max);
}

TEST(RenderDepthFormats, ConventionalDepthRanksAreTheFixedPointStepsNearerLarger) {
    auto context = createHeadlessContext({Backend::Auto, {}}, 64, 48);
    GlRenderer renderer(64, 48, DepthConvention::Conventional24);
    const MeshData cube = cubeMesh();
    renderer.uploadMeshes(std::span<const MeshData>(&cube, 1));
    renderer.setObjectMeshes(std::vector<uint32_t>{0, 0});
    ViewSetup view;
    view.projection = perspectiveFor(DepthConvention::Conventional24, glm::radians(90.0f),
                                     64.0f / 48, 0.1f, 1000.0f);
    const std::vector<glm::mat4> model_view = {glm::translate(glm::mat4(1.0f), {-1, 0, -3}),
                                               glm::translate(glm::mat4(1.0f), {4, 0, -30}) *
                                                   glm::scale(glm::mat4(1.0f), glm::vec3(6.0f))};
    renderer.setView(view, model_view);
    renderer.beginFrame();
    renderer.drawObject(0);
    renderer.drawObject(1);
    std::vector<uint32_t> ranks, ids;
    renderer.readDepthRanks(ranks);
    renderer.readObjectIds(ids);
    uint32_t near_min = UINT32_MAX, far_max = 0;
    for (size_t i = 0; i < ids.size(); ++i) {
        EXPECT_LE(ranks[i], 0xFFFFFFu) << "a 24-bit step";
        if (ids[i] == 0) {
            EXPECT_EQ(ranks[i], 0u);
        }
        if (ids[i] == 1) near_min = std::min(near_min, ranks[i]);
        if (ids[i] == 2) far_max = std::max(far_max, ranks[i]);
    }
    ASSERT_GT(far_max, 0u) << "the far cube shows";
    ASSERT_LT(near_min, UINT32_MAX) << "the near cube shows";
    EXPECT_GT(near_min, far_max);
}

TEST_P(RenderTest, TheDeviceKnowsWhichObjectsItDrewSinceTheSetBegan) {
    GlQueryDevice device(*renderer_, LatencyMode{});
    device.beginDrawnSet(3);
    renderer_->beginFrame();
    device.drawObject(1);
    EXPECT_FALSE(device.drew(0));
    EXPECT_TRUE(device.drew(1));
    EXPECT_FALSE(device.drew(2));
    EXPECT_FALSE(device.drew(7)) << "an object past the set is never drawn";
    device.beginDrawnSet(3);
    EXPECT_FALSE(device.drew(1)) << "a new set starts empty";
    device.drawObject(2);
    EXPECT_TRUE(device.drew(2));
}

// Conditional rendering (occsim/culling/contract/conditional_rendering.h) on the GL device: the
// driver skips what the query found hidden, nothing is read back, and the drawn set used for missed
// objects counts a conditional draw as drawn when its query passed samples.
TEST_P(RenderTest, ConditionalDrawsBehindAnOccluderAreSkippedAndTheOthersDrawn) {
    for (ConditionWait wait : {ConditionWait::Wait, ConditionWait::NoWait}) {
        GlQueryDevice device(*renderer_, LatencyMode{});
        ConditionalRendering* c = device.conditionalRendering();
        ASSERT_NE(c, nullptr);
        device.beginDrawnSet(3);
        renderer_->beginFrame();
        device.drawObject(0);
        const QueryId hidden = device.issueQuery(boxes_[1]);
        const QueryId visible = device.issueQuery(boxes_[2]);
        c->drawIf(hidden, 1, wait);
        c->drawIf(visible, 2, wait);
        c->release(hidden);
        c->release(visible);
        renderer_->finish();
        std::vector<uint32_t> ids;
        renderer_->readObjectIds(ids);
        EXPECT_GT(std::count(ids.begin(), ids.end(), 3u), 0) << "the side cube is drawn";
        device.resolveConditionalDraws();
        EXPECT_FALSE(device.drew(1)) << "its query passed nothing";
        EXPECT_TRUE(device.drew(2));
        EXPECT_EQ(device.counters().objects_drawn, 3u) << "submitted draws";
        EXPECT_EQ(device.counters().conditional_draws, 2u);
        EXPECT_EQ(device.counters().results_fetched, 0u) << "nothing read back";
        EXPECT_EQ(device.queriesInFlight(), 0u) << "released";
    }
}

TEST_P(RenderTest, ConditionalNoWaitUnderDeterministicLatencyDrawsUntilTheAnswerCountsAsReady) {
    for (uint32_t latency : {0u, 100u}) {
        GlQueryDevice device(*renderer_, LatencyMode{true, latency});
        ConditionalRendering& c = *device.conditionalRendering();
        device.beginDrawnSet(3);
        renderer_->beginFrame();
        device.drawObject(0);
        const QueryId hidden = device.issueQuery(boxes_[1]);
        c.drawIf(hidden, 1, ConditionWait::NoWait);
        c.release(hidden);
        renderer_->finish();
        device.resolveConditionalDraws();
        EXPECT_EQ(device.drew(1), latency == 100u)
            << "latency " << latency << ": drawn unconditionally only while not ready";
    }
}

// What the driver executed of the conditional draws, counted by GL_PRIMITIVES_GENERATED around
// each block, is real: GL_QUERY_WAIT skips the hidden cube (12 triangles) and nothing else, and
// under deterministic latency a NO_WAIT draw before its answer counts as ready executes.
TEST_P(RenderTest, ConditionalDrawsTheDriverSkippedAreCountedApartFromThoseSubmitted) {
    const uint64_t cube = renderer_->triangleCount(1);
    ASSERT_EQ(cube, 12u);
    auto skipped = [&](LatencyMode latency, ConditionWait wait) {
        GlQueryDevice device(*renderer_, latency);
        ConditionalRendering& c = *device.conditionalRendering();
        device.beginDrawnSet(3);
        renderer_->beginFrame();
        device.drawObject(0);
        const QueryId hidden = device.issueQuery(boxes_[1]);
        const QueryId visible = device.issueQuery(boxes_[2]);
        c.drawIf(hidden, 1, wait);
        c.drawIf(visible, 2, wait);
        c.release(hidden);
        c.release(visible);
        renderer_->finish();
        const GlQueryDevice::SkippedDraws s = device.skippedConditionalDraws();
        EXPECT_EQ(device.counters().objects_drawn, 3u) << "submitted, skipped ones included";
        EXPECT_EQ(device.counters().triangles_drawn, 3 * cube);
        // The next frame's set starts with nothing skipped.
        device.beginDrawnSet(3);
        EXPECT_EQ(device.skippedConditionalDraws().objects, 0u);
        return s;
    };
    const GlQueryDevice::SkippedDraws waited = skipped(LatencyMode{}, ConditionWait::Wait);
    EXPECT_EQ(waited.objects, 1u) << "the hidden cube, and only it";
    EXPECT_EQ(waited.triangles, cube);
    const GlQueryDevice::SkippedDraws early =
        skipped(LatencyMode{true, 100}, ConditionWait::NoWait);
    EXPECT_EQ(early.objects, 0u) << "not ready: drawn unconditionally";
    const GlQueryDevice::SkippedDraws late = skipped(LatencyMode{true, 0}, ConditionWait::NoWait);
    EXPECT_EQ(late.objects, 1u) << "ready: the condition is evaluated";
    // Measured NO_WAIT: the driver decides; never more skipped than hidden.
    EXPECT_LE(skipped(LatencyMode{}, ConditionWait::NoWait).objects, 1u);
}

TEST_P(RenderTest, AConditionOnABoxAroundTheEyeDrawsUnconditionally) {
    const float near_radius =
        static_cast<float>(nearPlaneCornerDistance(0.1, glm::radians(90.0), double(kW) / kH));
    setEye({0, 0, 0}, near_radius);
    GlQueryDevice device(*renderer_, LatencyMode{});
    device.beginDrawnSet(3);
    renderer_->beginFrame();
    device.drawObject(0);
    const Aabb around{{-10, -10, -10}, {10, 10, 10}};
    ASSERT_TRUE(renderer_->queryBoxNearEye(around));
    const QueryId q = device.issueQuery(around);
    device.conditionalRendering()->drawIf(q, 1, ConditionWait::Wait);
    device.conditionalRendering()->release(q);
    renderer_->finish();
    device.resolveConditionalDraws();
    EXPECT_TRUE(device.drew(1)) << "its samples mean nothing: drawn, as takeAnswer says visible";
}

TEST_P(RenderTest, PngEncodingProducesAValidPngSignature) {
    renderer_->beginFrame();
    renderer_->drawObject(0);
    std::vector<uint8_t> rgba;
    renderer_->readColor(rgba);
    const std::vector<uint8_t> png = encodePngBottomUp(rgba, kW, kH);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png[1], 'P');
    EXPECT_EQ(png[2], 'N');
    EXPECT_EQ(png[3], 'G');
}

INSTANTIATE_TEST_SUITE_P(Backends, RenderTest, ::testing::ValuesIn(testing::testedBackends()),
                         testing::backendTestName);

// The same frame on every backend: the same object IDs, pixel for pixel (both are Mesa's llvmpipe
// here; on a GPU the rasteriser differs and only the counts of deterministic runs must agree).
TEST(HeadlessBackends, EveryBackendRendersTheSameObjectIds) {
    std::vector<std::vector<uint32_t>> images;
    for (Backend backend : testing::testedBackends()) {
        auto context = createHeadlessContext({backend, {}}, 64, 48);
        GlRenderer renderer(64, 48);
        const MeshData cube = cubeMesh();
        renderer.uploadMeshes(std::span<const MeshData>(&cube, 1));
        renderer.setObjectMeshes(std::vector<uint32_t>{0});
        ViewSetup view;
        view.projection = reverseZPerspective(glm::radians(60.0f), 64.0f / 48.0f, 0.1f, 100.0f);
        const std::vector<glm::mat4> model_view = {
            glm::translate(glm::mat4(1.0f), {0.3f, 0.1f, -3.0f})};
        renderer.setView(view, model_view);
        renderer.beginFrame();
        renderer.drawObject(0);
        images.emplace_back();
        renderer.readObjectIds(images.back());
        EXPECT_GT(std::count(images.back().begin(), images.back().end(), 1u), 100);
    }
    for (size_t i = 1; i < images.size(); ++i) EXPECT_EQ(images[i], images[0]);
}

TEST(HeadlessBackends, AutoTakesEglWhereEglIsThere) {
    auto context = createHeadlessContext({Backend::Auto, {}}, 16, 16);
    EXPECT_EQ(context->info().backend, Backend::Egl);
    EXPECT_EQ(context->info().device, 0u);
}

TEST(HeadlessBackends, EglListsTheSoftwareDeviceWithItsStrings) {
    const std::vector<EglDeviceInfo> devices = listEglDevices();
    ASSERT_FALSE(devices.empty());
    bool llvmpipe = false;
    for (const EglDeviceInfo& d : devices) {
        EXPECT_TRUE(d.problem.empty()) << d.problem;
        llvmpipe |= d.context.renderer.find("llvmpipe") != std::string::npos;
        if (d.context.renderer.find("llvmpipe") != std::string::npos) {
            EXPECT_EQ(d.kind, "software");
            EXPECT_FALSE(d.context.gpu_time_meaningful);
        }
    }
    EXPECT_TRUE(llvmpipe);
}

// Asserts `make` throws BackendUnavailable whose one-line message contains every part.
template <class F>
void expectUnavailable(F&& make, std::initializer_list<const char*> parts) {
    try {
        make();
        ADD_FAILURE() << "no BackendUnavailable";
    } catch (const BackendUnavailable& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        for (const char* part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
    }
}

TEST(HeadlessBackends, ADeviceOutOfRangeNamesTheIndexAndWhatEglLists) {
    const auto count = static_cast<uint32_t>(listEglDevices().size());
    expectUnavailable(
        [&] {
            createHeadlessContext({Backend::Egl, count}, 16, 16);
        },
        {"--device", "out of range", "software"});
    expectUnavailable(
        [&] {
            createHeadlessContext({Backend::Auto, count + 5}, 16, 16);
        },
        {"--device", "out of range"});
}

// The colour buffer Mesa was given outlives the context (Mesa keeps the pointer in a global list
// and copies frames into it: render/osmesa_colour_buffer.h): after the context is gone nothing is
// current, and the buffer is still allocated, and still writable, also once a larger context took
// a larger one.
TEST(HeadlessBackends, OsmesaColourBufferOutlivesEveryContextThatUsedIt) {
#if OCCSIM_HAVE_OSMESA
    void* first = nullptr;
    {
        auto context = createHeadlessContext({Backend::OsMesa, {}}, 64, 48);
        int w = 0, h = 0, format = 0;
        ASSERT_TRUE(OSMesaGetColorBuffer(OSMesaGetCurrentContext(), &w, &h, &format, &first));
        EXPECT_EQ(w, 64);
        EXPECT_EQ(h, 48);
        EXPECT_TRUE(osmesaColourBufferIsKept(first));
    }
    EXPECT_EQ(OSMesaGetCurrentContext(), nullptr) << "unbound before it was destroyed";
    EXPECT_TRUE(osmesaColourBufferIsKept(first));
    {
        auto larger = createHeadlessContext({Backend::OsMesa, {}}, 256, 192);
        void* second = nullptr;
        int w = 0, h = 0, format = 0;
        ASSERT_TRUE(OSMesaGetColorBuffer(OSMesaGetCurrentContext(), &w, &h, &format, &second));
        EXPECT_NE(second, first) << "a larger buffer for a larger context";
        EXPECT_TRUE(osmesaColourBufferIsKept(second));
    }
    EXPECT_TRUE(osmesaColourBufferIsKept(first));
    std::fill_n(static_cast<unsigned char*>(first), 64 * 48 * 4, 0);  // what a late flush does
#else
    GTEST_SKIP() << "this build has no OSMesa";
#endif
    EXPECT_FALSE(osmesaColourBufferIsKept(this));
    EXPECT_EQ(osmesaColourBuffer(8, 8), osmesaColourBuffer(4, 4)) << "a block that fits is shared";
}

TEST(HeadlessBackends, OsmesaHasNoDevices) {
    expectUnavailable(
        [] {
            createHeadlessContext({Backend::OsMesa, 0u}, 16, 16);
        },
        {"--device 0", "only the EGL backend"});
}

TEST(HeadlessBackends, OsmesaInABuildWithoutItSaysSo) {
    if (osmesaAvailable())
        GTEST_SKIP() << "this build has OSMesa (the no-osmesa preset checks this)";
    expectUnavailable(
        [] {
            createHeadlessContext({Backend::OsMesa, {}}, 16, 16);
        },
        {"--backend osmesa", "no OSMesa", "OCCSIM_WITH_OSMESA=OFF"});
}

TEST(HeadlessBackends, BackendNamesRoundTrip) {
    for (Backend b : {Backend::Auto, Backend::Egl, Backend::OsMesa})
        EXPECT_EQ(parseBackend(backendName(b)), b);
    EXPECT_FALSE(parseBackend("vulkan"));
    EXPECT_FALSE(parseBackend("EGL"));
}

GlCapabilities enough() {
    GlCapabilities c;
    c.major = 4;
    c.minor = 5;
    c.core_profile = true;
    c.extensions = requiredGlExtensions();
    c.renderer = "Some GPU";
    c.version = "4.5.0 Vendor 1.2";
    return c;
}

TEST(GlRequirements, A45CoreContextWithTheExtensionsIsEnough) {
    EXPECT_EQ(checkGlRequirements(enough()), "");
    GlCapabilities newer = enough();
    newer.minor = 6;
    EXPECT_EQ(checkGlRequirements(newer), "");
}

TEST(GlRequirements, BelowFourFiveNamesTheVersionFound) {
    GlCapabilities old = enough();
    old.minor = 3;
    old.version = "4.3 (Core Profile) Mesa 20.0";
    const std::string problem = checkGlRequirements(old);
    EXPECT_NE(problem.find("needs an OpenGL 4.5 core"), std::string::npos) << problem;
    EXPECT_NE(problem.find("found OpenGL 4.3 core"), std::string::npos) << problem;
    EXPECT_NE(problem.find("Some GPU"), std::string::npos) << problem;
    GlCapabilities compatibility = enough();
    compatibility.core_profile = false;
    EXPECT_NE(checkGlRequirements(compatibility).find("found OpenGL 4.5 ("), std::string::npos);
}

TEST(GlRequirements, AMissingExtensionIsNamed) {
    GlCapabilities c = enough();
    c.extensions = {"GL_ARB_occlusion_query2"};
    const std::string problem = checkGlRequirements(c);
    EXPECT_NE(problem.find("GL_ARB_timer_query"), std::string::npos) << problem;
    EXPECT_EQ(problem.find("GL_ARB_occlusion_query2,"), std::string::npos) << problem;
}

TEST(GlRequirements, TheDriverIsTheVersionStringWithoutTheApiVersion) {
    EXPECT_EQ(driverOfVersion("4.5 (Core Profile) Mesa 22.3.6"), "Mesa 22.3.6");
    EXPECT_EQ(driverOfVersion("4.6.0 NVIDIA 535.54.03"), "NVIDIA 535.54.03");
    EXPECT_EQ(driverOfVersion("4.6 (Core Profile) Mesa 23.2.1 (LLVM 15.0.7)"),
              "Mesa 23.2.1 (LLVM 15.0.7)");
    EXPECT_EQ(driverOfVersion("4.5"), "4.5");
}

TEST(GlRequirements, SoftwareRenderersAreRecognised) {
    EXPECT_TRUE(isSoftwareRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
    EXPECT_TRUE(isSoftwareRenderer("softpipe"));
    EXPECT_TRUE(isSoftwareRenderer("Google SwiftShader"));
    EXPECT_FALSE(isSoftwareRenderer("NVIDIA GeForce RTX 3080/PCIe/SSE2"));
    EXPECT_FALSE(
        isSoftwareRenderer("AMD Radeon RX 6800 (radeonsi, navi21, LLVM 15.0.6, DRM 3.49)"));
}

}  // namespace
}  // namespace occsim
