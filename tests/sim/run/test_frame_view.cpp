// The camera of one frame (sim/run/frame_view.h): the culling view in the culling frame, exact far
// from the origin; the render view in world coordinates with the scenario's depth convention; the
// lens's near radius and viewport handed to both; straight up or down still a camera; a light's
// render view holds its whole box, nearer the light nearer in depth, next to the origin and far;
// its culling view keeps a box inside the light's box and culls one beside it, its eye far up the
// light so that the tree's front-to-back order follows the light; stereo eyes either side.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>

#include "occsim/culling/geometry/frustum.h"
#include "sim/run/frame_view.h"
#include "sim/scenario/scenario.h"
#include "sim/world/light_view.h"

namespace occsim {
namespace {

CameraSpec lens() {
    CameraSpec camera;
    camera.fov_y_deg = 60.0;
    camera.near_m = 0.5;
    camera.far_m = 200.0;
    camera.keyframes = {CameraKeyframe{0.0, {0.0, 2.0, 10.0}, {0.0, 2.0, 0.0}}};
    return camera;
}

Aabb cubeAt(const glm::vec3& centre, float half) {
    return Aabb{centre - glm::vec3(half), centre + glm::vec3(half)};
}

TEST(FrameView, TheCullingViewIsTheCameraRelativeToTheCullingOriginFarFromTheWorldOrigin) {
    // 10^6 m away, in single precision a step of 0.0625 m: the eye in the culling frame is
    // computed in double before it is rounded, so it is exact to the millimetre.
    const glm::dvec3 far{1.0e6 + 0.123, 3.0, -1.0e6 + 0.456};
    const CameraPose pose{far, far + glm::dvec3(0.0, 0.0, -1.0)};
    const glm::dvec3 origin{1.0e6, 0.0, -1.0e6};
    const FrameView view = makeFrameView(lens(), pose, 320, 240, origin);
    EXPECT_NEAR(view.cull.eye.x, 0.123f, 1e-6f);
    EXPECT_NEAR(view.cull.eye.y, 3.0f, 1e-6f);
    EXPECT_NEAR(view.cull.eye.z, 0.456f, 1e-6f);
    EXPECT_EQ(view.render.eye, far);
    EXPECT_EQ(view.render.box_origin, origin);

    // A small box 5 m ahead is in the culling frustum; the same box behind the eye, or beyond
    // the far plane, is not.
    const glm::vec3 eye = view.cull.eye;
    EXPECT_NE(classify(view.cull.frustum, cubeAt(eye + glm::vec3(0, 0, -5), 0.01f)),
              FrustumTest::Outside);
    EXPECT_EQ(classify(view.cull.frustum, cubeAt(eye + glm::vec3(0, 0, 5), 0.01f)),
              FrustumTest::Outside);
    EXPECT_EQ(classify(view.cull.frustum, cubeAt(eye + glm::vec3(0, 0, -210), 1.0f)),
              FrustumTest::Outside);
}

TEST(FrameView, TheFieldOfViewAndAspectBoundTheCullingFrustum) {
    const CameraSpec camera = lens();
    const CameraPose pose{{0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}};
    // 10 m ahead the frustum is 10 * tan(30 deg) = 5.77 m high each side of the axis and twice
    // that wide at 2:1.
    const FrameView view = makeFrameView(camera, pose, 400, 200, glm::dvec3(0.0));
    const double half_height = 10.0 * std::tan(glm::radians(30.0));
    const auto at = [&](double x, double y) {
        return classify(
            view.cull.frustum,
            cubeAt(glm::vec3(static_cast<float>(x), static_cast<float>(y), -10.0f), 0.01f));
    };
    EXPECT_NE(at(0.0, half_height - 0.1), FrustumTest::Outside);
    EXPECT_EQ(at(0.0, half_height + 0.1), FrustumTest::Outside);
    EXPECT_NE(at(2.0 * half_height - 0.1, 0.0), FrustumTest::Outside);
    EXPECT_EQ(at(2.0 * half_height + 0.1, 0.0), FrustumTest::Outside);
    EXPECT_EQ(view.cull.viewport_width, 400u);
    EXPECT_EQ(view.cull.viewport_height, 200u);
    // The near radius both views guard with: eye to a corner of the near plane.
    EXPECT_FLOAT_EQ(view.cull.near_radius,
                    static_cast<float>(nearPlaneCornerDistance(0.5, glm::radians(60.0), 2.0)));
    EXPECT_EQ(view.render.near_radius, view.cull.near_radius);
}

TEST(FrameView, TheRenderProjectionFollowsTheScenariosDepthConvention) {
    Scenario scenario;
    EXPECT_EQ(depthConventionOf(scenario), DepthConvention::ReverseFloat);
    scenario.conventional_depth = true;
    EXPECT_EQ(depthConventionOf(scenario), DepthConvention::Conventional24);

    const CameraSpec camera = lens();
    const CameraPose pose{{0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}};
    // A point on the near plane: depth 1 under reverse-Z (GL_ZERO_TO_ONE), -1 conventionally;
    // the far plane the other way round.
    const auto ndcDepth = [&](DepthConvention depth, double distance) {
        const FrameView view = makeFrameView(camera, pose, 320, 240, glm::dvec3(0.0), depth);
        const glm::vec4 clip = view.render.projection * view.render.view_rotation *
                               glm::vec4(0.0f, 0.0f, -static_cast<float>(distance), 1.0f);
        return clip.z / clip.w;
    };
    EXPECT_NEAR(ndcDepth(DepthConvention::ReverseFloat, 0.5), 1.0f, 1e-5f);
    EXPECT_NEAR(ndcDepth(DepthConvention::ReverseFloat, 200.0), 0.0f, 1e-5f);
    EXPECT_NEAR(ndcDepth(DepthConvention::Conventional24, 0.5), -1.0f, 1e-5f);
    EXPECT_NEAR(ndcDepth(DepthConvention::Conventional24, 200.0), 1.0f, 1e-5f);
}

TEST(FrameView, ACameraLookingStraightDownStillSeesTheGroundBelow) {
    // y cannot be the up vector looking down y: a view made with it would be degenerate (NaN).
    const CameraPose pose{{0.0, 50.0, 0.0}, {0.0, 0.0, 0.0}};
    const FrameView view = makeFrameView(lens(), pose, 320, 240, glm::dvec3(0.0));
    for (int i = 0; i < 6; ++i) {
        const glm::vec4 p = view.cull.frustum.planes[i];
        EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
                    std::isfinite(p.w))
            << "plane " << i;
    }
    EXPECT_NE(classify(view.cull.frustum, cubeAt(glm::vec3(0.0f, 0.0f, 0.0f), 1.0f)),
              FrustumTest::Outside);
    EXPECT_EQ(classify(view.cull.frustum, cubeAt(glm::vec3(0.0f, 60.0f, 0.0f), 1.0f)),
              FrustumTest::Outside);
}

TEST(FrameView, AFrameOfThePathIsThePoseTheCameraPathGivesAtThatTime) {
    CameraSpec camera = lens();
    camera.keyframes = {CameraKeyframe{0.0, {0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}},
                        CameraKeyframe{2.0, {10.0, 0.0, 0.0}, {10.0, 0.0, -1.0}}};
    const FrameView view = makeFrameView(camera, 1.0, 320, 240, glm::dvec3(0.0));
    const FrameView posed =
        makeFrameView(camera, sampleCameraPath(camera, 1.0), 320, 240, glm::dvec3(0.0));
    EXPECT_EQ(view.render.eye, posed.render.eye);
    EXPECT_EQ(view.cull.eye, posed.cull.eye);
    EXPECT_NEAR(view.render.eye.x, 5.0, 1e-9);
}

// Every point of a directional light's box projects inside the view, in depth between near and
// far, a point nearer the light nearer; a point beside the box projects outside. In double, as the
// renderer computes eye-relative positions, next to the origin and 10^6 m from it.
TEST(LightRenderView, HoldsItsWholeBoxNearerTheLightNearer) {
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, 0.0, -1e6)}) {
        for (const DepthConvention depth :
             {DepthConvention::ReverseFloat, DepthConvention::Conventional24}) {
            const WorldBox scene{origin + glm::dvec3(-50, 0, -50), origin + glm::dvec3(50, 30, 50)};
            const auto corners = viewFrustumCorners(origin + glm::dvec3(0, 2, 40),
                                                    origin + glm::dvec3(0, 0, 0), 60, 1.5, 0.1, 80);
            const LightBox box = fitDirectionalLight(glm::dvec3(0.4, -1.0, 0.3), corners, scene);
            ASSERT_FALSE(box.empty);
            const ViewSetup view = makeLightRenderView(box, origin, depth);
            const auto project = [&](const glm::dvec3& light_space) {
                const glm::dvec3 world = box.right * light_space.x + box.up * light_space.y +
                                         box.forward * light_space.z;
                const glm::vec4 clip = view.projection * view.view_rotation *
                                       glm::vec4(glm::vec3(world - view.eye), 1);
                return glm::vec3(clip) / clip.w;
            };
            const bool reverse = depth == DepthConvention::ReverseFloat;
            const float z_lo = reverse ? 0.0f : -1.0f;
            for (int i = 0; i < 8; ++i) {
                const glm::dvec3 l((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                                   (i & 4) ? box.max.z : box.min.z);
                const glm::vec3 ndc = project(l);
                EXPECT_LE(std::abs(ndc.x), 1.0f + 1e-4f) << i;
                EXPECT_LE(std::abs(ndc.y), 1.0f + 1e-4f) << i;
                EXPECT_GT(ndc.z, z_lo) << i;
                EXPECT_LT(ndc.z, 1.0f) << i;
            }
            const glm::dvec3 mid = 0.5 * (box.min + box.max);
            const float near_z = project({mid.x, mid.y, box.min.z}).z;
            const float far_z = project({mid.x, mid.y, box.max.z}).z;
            EXPECT_TRUE(reverse ? near_z > far_z : near_z < far_z);
            EXPECT_GT(std::abs(project({box.max.x + 1.0, mid.y, mid.z}).x), 1.0f);
        }
    }
}

// The light's view as the cullers see it (makeLightCullView): an object box inside the light's box
// is inside its frustum, one beside it across the light or beyond its far end is outside; its
// view-projection maps the box into clip space as the render view does; its eye lies up the light
// from every point of the box, farther than any distance across it, so that for every split plane
// the eye's side is the side the light comes from; the viewport is the map's. Next to the origin
// and 10^6 m from it (the culling frame is relative to the culling origin).
TEST(LightCullView, ItsFrustumIsTheLightsBoxAndItsEyeLiesUpTheLight) {
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, 0.0, -1e6)}) {
        const WorldBox scene{origin + glm::dvec3(-50, 0, -50), origin + glm::dvec3(50, 30, 50)};
        const auto corners = viewFrustumCorners(origin + glm::dvec3(0, 2, 40),
                                                origin + glm::dvec3(0, 0, 0), 60, 1.5, 0.1, 80);
        const glm::dvec3 direction = glm::normalize(glm::dvec3(0.4, -1.0, 0.3));
        const LightBox box = fitDirectionalLight(direction, corners, scene);
        ASSERT_FALSE(box.empty);
        const CullView view = makeLightCullView(box, origin, 1024);
        EXPECT_EQ(view.kind, ViewKind::Light);
        EXPECT_EQ(view.viewport_width, 1024u);
        EXPECT_EQ(view.viewport_height, 1024u);
        EXPECT_EQ(view.near_radius, 0.0f);
        // Light space to the culling frame.
        const auto at = [&](const glm::dvec3& l) {
            return glm::vec3(box.right * l.x + box.up * l.y + box.forward * l.z - origin);
        };
        const glm::dvec3 mid = 0.5 * (box.min + box.max);
        const glm::dvec3 size = box.max - box.min;
        const FrustumPlanes planes = planeTableOf(view.frustum);
        EXPECT_NE(classify(planes, cubeAt(at(mid), 0.5f)), FrustumTest::Outside);
        EXPECT_NE(classify(planes, cubeAt(at({box.min.x + 0.5, mid.y, box.min.z + 0.5}), 0.4f)),
                  FrustumTest::Outside);
        EXPECT_EQ(classify(planes, cubeAt(at({box.max.x + 2.0, mid.y, mid.z}), 0.5f)),
                  FrustumTest::Outside);
        EXPECT_EQ(classify(planes, cubeAt(at({mid.x, mid.y, box.max.z + 4.0}), 0.5f)),
                  FrustumTest::Outside);
        // A corner of the box in clip space: inside [-1, 1]^3.
        for (int i = 0; i < 8; ++i) {
            const glm::dvec3 l((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                               (i & 4) ? box.max.z : box.min.z);
            const glm::vec4 clip = view.view_projection * glm::vec4(at(l), 1.0f);
            EXPECT_LE(std::abs(clip.x / clip.w), 1.0f + 1e-3f) << i;
            EXPECT_LE(std::abs(clip.y / clip.w), 1.0f + 1e-3f) << i;
            EXPECT_LE(std::abs(clip.z / clip.w), 1.0f) << i;
        }
        // Up the light from the box's centre, farther than the box is across.
        const glm::dvec3 to_eye = glm::dvec3(view.eye) - glm::dvec3(at(mid));
        EXPECT_GT(glm::dot(to_eye, -box.forward), 100.0 * glm::length(size));
        EXPECT_GT(glm::dot(glm::normalize(to_eye), -box.forward), 0.999999);
        // For a split plane through the box's centre on each axis, the eye is on the side the light
        // comes from (where the light travels toward +axis, below the split).
        for (int axis = 0; axis < 3; ++axis) {
            if (std::abs(direction[axis]) < 1e-3) continue;
            const float split = at(mid)[axis];
            EXPECT_EQ(view.eye[axis]<split, direction[axis]> 0.0) << axis;
        }
    }
}

// Stereo, eyes 1 m apart for clear margins: each eye half a metre to its side of the camera,
// looking the same way; the enclosing view keeps what either eye sees 5 m ahead (the middle
// camera's frustum there spans x in +-3.85 m, each eye's is shifted by 0.5 m) and culls what
// neither does; the render view carries the separation and a near radius grown by half of it.
TEST(FrameView, StereoEyesSitEitherSideOfTheCameraAndTheEnclosingViewKeepsWhatEitherSees) {
    const CameraPose pose{{0.0, 2.0, 10.0}, {0.0, 2.0, 0.0}};
    const FrameView middle = makeFrameView(lens(), pose, 320, 240, glm::dvec3(0.0));
    const StereoViews stereo = makeStereoViews(lens(), pose, 1.0, 320, 240, glm::dvec3(0.0));
    EXPECT_NEAR(stereo.left.eye.x, -0.5f, 1e-6f);
    EXPECT_NEAR(stereo.right.eye.x, 0.5f, 1e-6f);
    EXPECT_NEAR(stereo.left.eye.z, 10.0f, 1e-6f);
    EXPECT_EQ(stereo.left.kind, ViewKind::LeftEye);
    EXPECT_EQ(stereo.right.kind, ViewKind::RightEye);
    EXPECT_EQ(stereo.enclosing.kind, ViewKind::Camera);
    EXPECT_EQ(stereo.render.eye_separation_m, 1.0);
    EXPECT_NEAR(stereo.left_render.eye.x, -0.5, 1e-12) << "each eye's own render view";
    EXPECT_NEAR(stereo.right_render.eye.x, 0.5, 1e-12);
    EXPECT_EQ(stereo.right_render.eye_separation_m, 0.0);
    EXPECT_FLOAT_EQ(stereo.render.near_radius, middle.render.near_radius + 0.5f);
    EXPECT_FLOAT_EQ(stereo.enclosing.near_radius, middle.cull.near_radius + 0.5f);
    const Aabb left_only = cubeAt({-4.1f, 2.0f, 5.0f}, 0.05f);
    const Aabb right_only = cubeAt({4.1f, 2.0f, 5.0f}, 0.05f);
    const Aabb neither = cubeAt({-4.6f, 2.0f, 5.0f}, 0.05f);
    EXPECT_EQ(classify(middle.cull.frustum, left_only), FrustumTest::Outside);
    EXPECT_EQ(classify(middle.cull.frustum, right_only), FrustumTest::Outside);
    EXPECT_NE(classify(stereo.left.frustum, left_only), FrustumTest::Outside);
    EXPECT_EQ(classify(stereo.right.frustum, left_only), FrustumTest::Outside);
    EXPECT_NE(classify(stereo.right.frustum, right_only), FrustumTest::Outside);
    EXPECT_NE(classify(stereo.enclosing.frustum, left_only), FrustumTest::Outside);
    EXPECT_NE(classify(stereo.enclosing.frustum, right_only), FrustumTest::Outside);
    EXPECT_EQ(classify(stereo.enclosing.frustum, neither), FrustumTest::Outside);
    EXPECT_EQ(classify(stereo.enclosing.frustum, cubeAt({0.0f, 2.0f, 15.0f}, 0.05f)),
              FrustumTest::Outside)
        << "behind the eyes";
}

}  // namespace
}  // namespace occsim
