#include "sim/run/frame_view.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace occsim {

DepthConvention depthConventionOf(const Scenario& scenario) {
    return scenario.conventional_depth ? DepthConvention::Conventional24
                                       : DepthConvention::ReverseFloat;
}

FrameView makeFrameView(const CameraSpec& camera, double time_s, uint32_t width, uint32_t height,
                        const glm::dvec3& culling_origin, DepthConvention depth) {
    return makeFrameView(camera, sampleCameraPath(camera, time_s), width, height, culling_origin,
                         depth);
}

FrameView makeFrameView(const CameraSpec& camera, const CameraPose& pose, uint32_t width,
                        uint32_t height, const glm::dvec3& culling_origin, DepthConvention depth) {
    const glm::dvec3 forward = glm::normalize(pose.target - pose.position);
    const glm::dvec3 up = cameraWorldUp(forward);
    const double aspect = static_cast<double>(width) / height;
    const double fov = glm::radians(camera.fov_y_deg);

    FrameView view;
    view.render.eye = pose.position;
    view.render.box_origin = culling_origin;
    view.render.view_rotation = glm::mat4(glm::lookAt(glm::dvec3(0.0), forward, up));
    view.render.projection =
        perspectiveFor(depth, static_cast<float>(fov), static_cast<float>(aspect),
                       static_cast<float>(camera.near_m), static_cast<float>(camera.far_m));
    // Culling uses the conventional OpenGL projection, in the culling frame: the eye relative to
    // the culling origin is computed in double, so the planes are as precise as the boxes.
    const glm::dvec3 eye = pose.position - culling_origin;
    const glm::dmat4 view_projection = glm::perspective(fov, aspect, camera.near_m, camera.far_m) *
                                       glm::lookAt(eye, eye + forward, up);
    view.cull.eye = glm::vec3(eye);
    view.cull.frustum =
        frustumFromViewProjection(view_projection);  // planes in double: deep ranges
    view.cull.near_radius = static_cast<float>(nearPlaneCornerDistance(camera.near_m, fov, aspect));
    view.cull.view_projection = glm::mat4(view_projection);
    view.cull.viewport_width = width;
    view.cull.viewport_height = height;
    view.render.near_radius = view.cull.near_radius;
    return view;
}

StereoViews makeStereoViews(const CameraSpec& camera, const CameraPose& pose, double separation_m,
                            uint32_t width, uint32_t height, const glm::dvec3& culling_origin,
                            DepthConvention depth) {
    const FrameView middle = makeFrameView(camera, pose, width, height, culling_origin, depth);
    // The view's x axis in the world, as lookAt makes it (forward x up).
    const glm::dvec3 forward = glm::normalize(pose.target - pose.position);
    const glm::dvec3 half =
        0.5 * separation_m * glm::normalize(glm::cross(forward, cameraWorldUp(forward)));
    const CameraPose left_pose{pose.position - half, pose.target - half};
    const CameraPose right_pose{pose.position + half, pose.target + half};
    StereoViews views;
    const FrameView left = makeFrameView(camera, left_pose, width, height, culling_origin, depth);
    const FrameView right = makeFrameView(camera, right_pose, width, height, culling_origin, depth);
    views.left = left.cull;
    views.right = right.cull;
    views.left_render = left.render;
    views.right_render = right.render;
    views.left.kind = ViewKind::LeftEye;
    views.right.kind = ViewKind::RightEye;
    const float grown = middle.cull.near_radius + static_cast<float>(0.5 * separation_m);
    views.render = middle.render;
    views.render.eye_separation_m = separation_m;
    views.render.near_radius = grown;
    views.enclosing = middle.cull;
    views.enclosing.frustum.planes[0] = views.left.frustum.planes[0];
    views.enclosing.frustum.planes[1] = views.right.frustum.planes[1];
    views.enclosing.near_radius = grown;
    return views;
}

namespace {

// A directional light's orthographic view of its box (docs/views.md): the eye 2 m before the box's
// near face on its centre line, the near plane 1 m from the eye and the far one 1 m past the box,
// the whole box strictly inside, its faces clear of both planes. World coordinates, double.
struct LightEye {
    glm::dvec3 eye;        // light space is measured from the world origin along right, up, forward
    glm::dvec2 half;       // the box's half-extents across the light
    double near_m, far_m;  // the planes' distances from the eye
    glm::dmat3 rotation;   // world to view: x along right, y along up, looking down -z = forward
};

LightEye lightEyeOf(const LightBox& box) {
    constexpr double kStandOff = 2.0, kNear = 1.0;
    const glm::dvec2 centre = 0.5 * (glm::dvec2(box.min) + glm::dvec2(box.max));
    return LightEye{
        box.right * centre.x + box.up * centre.y + box.forward * (box.min.z - kStandOff),
        0.5 * (glm::dvec2(box.max) - glm::dvec2(box.min)), kNear,
        box.max.z - box.min.z + kStandOff + kNear,
        glm::transpose(glm::dmat3(box.right, box.up, -box.forward))};
}

}  // namespace

CullView makeLightCullView(const LightBox& box, const glm::dvec3& culling_origin,
                           uint32_t map_size) {
    const LightEye light = lightEyeOf(box);
    // The render view's eye in the culling frame (the difference in double: 10^6 m out too).
    const glm::dvec3 eye = light.eye - culling_origin;
    const glm::dmat4 view_projection = glm::ortho(-light.half.x, light.half.x, -light.half.y,
                                                  light.half.y, light.near_m, light.far_m) *
                                       glm::dmat4(light.rotation) *
                                       glm::translate(glm::dmat4(1.0), -eye);
    CullView cull;
    cull.kind = ViewKind::Light;
    const double behind = kLightEyeDistance * std::max(glm::length(box.max - box.min), 1.0);
    cull.eye = glm::vec3(eye - box.forward * behind);
    cull.frustum = frustumFromViewProjection(view_projection);
    cull.near_radius = 0.0f;
    cull.view_projection = glm::mat4(view_projection);
    cull.viewport_width = map_size;
    cull.viewport_height = map_size;
    return cull;
}

ViewSetup makeLightRenderView(const LightBox& box, const glm::dvec3& culling_origin,
                              DepthConvention depth) {
    const LightEye light = lightEyeOf(box);
    ViewSetup view;
    view.eye = light.eye;
    view.box_origin = culling_origin;
    view.view_rotation = glm::mat4(glm::dmat4(light.rotation));
    view.projection =
        orthographicFor(depth, static_cast<float>(-light.half.x), static_cast<float>(light.half.x),
                        static_cast<float>(-light.half.y), static_cast<float>(light.half.y),
                        static_cast<float>(light.near_m), static_cast<float>(light.far_m));
    return view;
}

}  // namespace occsim
