// The camera of one frame, as the culler (culling frame, conventional projection) and the
// renderer (world coordinates, the scenario's depth convention) each need it.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>

#include "occsim/culling/contract/culler.h"
#include "render/gl_renderer.h"
#include "sim/scenario/scenario.h"
#include "sim/world/camera_path.h"
#include "sim/world/light_view.h"

namespace occsim {

// The view of one frame: everything a culler and the renderer need from the camera.
struct FrameView {
    CullView cull;
    ViewSetup render;
};

// The camera of one frame. The culling view (eye, frustum) is relative to `culling_origin`
// (Scene::culling_origin), like the object boxes and the tree; the render view is in world
// coordinates.
FrameView makeFrameView(const CameraSpec& camera, double time_s, uint32_t width, uint32_t height,
                        const glm::dvec3& culling_origin,
                        DepthConvention depth = DepthConvention::ReverseFloat);
// The same for a given pose; `camera` supplies the lens (field of view, near and far planes).
FrameView makeFrameView(const CameraSpec& camera, const CameraPose& pose, uint32_t width,
                        uint32_t height, const glm::dvec3& culling_origin,
                        DepthConvention depth = DepthConvention::ReverseFloat);

// A stereo frame's views (docs/views.md): two eyes `separation_m` apart on the camera's x axis,
// the camera midway, their axes parallel, each eye `width` x `height` pixels (the renderer draws
// them one above the other: GlRenderer, ViewSetup::eye_separation_m).
struct StereoViews {
    // The camera's render view with the separation set and its near radius grown by half the
    // separation: a box within an eye's near radius of that eye is within it of the midpoint, so
    // the renderer's near-eye guard holds for either eye.
    ViewSetup render;
    // Each eye's own culling view, for a culling pass per eye (ViewKind::LeftEye, RightEye).
    CullView left, right;
    // Each eye's own render view (no separation): what turns a pixel of its half of the
    // framebuffer back into a point (the receiver mask).
    ViewSetup left_render, right_render;
    // One culling view around both (ViewKind::Camera): the left eye's left plane, the right eye's
    // right plane and the camera's other four, which the eyes share (an eye's top, bottom, near and
    // far planes contain the x axis it is shifted along). The camera's eye and view-projection, the
    // near radius grown as the render view's.
    CullView enclosing;
};
StereoViews makeStereoViews(const CameraSpec& camera, const CameraPose& pose, double separation_m,
                            uint32_t width, uint32_t height, const glm::dvec3& culling_origin,
                            DepthConvention depth = DepthConvention::ReverseFloat);

// A directional light's view for its shadow pass (docs/views.md), in world coordinates: the eye
// 2 m before the box's near face on its centre line, looking down the light, and an orthographic
// projection of the box (near plane 1 m from the eye, far 1 m past the box) in `depth`'s
// convention. `box` not empty.
ViewSetup makeLightRenderView(const LightBox& box, const glm::dvec3& culling_origin,
                              DepthConvention depth = DepthConvention::ReverseFloat);

// The same light's view as the cullers see it (ViewKind::Light), relative to `culling_origin`: the
// frustum of makeLightRenderView's box (planes in double), its conventional OpenGL
// view-projection, a viewport of the map's `map_size` texels a side, and no near radius (the box
// starts at the scene's nearest point to the light, so no object's box reaches its near plane).
// The eye, which an orthographic view does not have, stands kLightEyeDistance box diagonals
// behind the near face's centre along the light: the cullers' front-to-back orders and distances
// then follow the light's direction (a split plane misorders only where the light runs within
// 1/(2 kLightEyeDistance) of parallel to it, where nothing is in front of anything anyway).
inline constexpr double kLightEyeDistance = 1000.0;
CullView makeLightCullView(const LightBox& box, const glm::dvec3& culling_origin,
                           uint32_t map_size);

// The renderer's depth convention a scenario asks for.
DepthConvention depthConventionOf(const Scenario& scenario);

}  // namespace occsim
