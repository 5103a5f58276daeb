// A camera for the overlay tests of this folder: at `eye`, looking down -z, 90 degrees, on a
// 64 x 64 canvas, with a count of the canvas's pixels of one colour.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "render/gl_renderer.h"
#include "sim/output/raster_canvas.h"

namespace occsim::testing {

inline constexpr uint32_t kOverlaySize = 64;
inline constexpr double kOverlayNear = 0.1;

inline ViewSetup overlayView(glm::dvec3 eye = glm::dvec3(0.0),
                             glm::dvec3 box_origin = glm::dvec3(0.0)) {
    ViewSetup view;
    view.eye = eye;
    view.box_origin = box_origin;
    view.view_rotation = glm::mat4(1.0f);
    view.projection =
        reverseZPerspective(glm::radians(90.0f), 1.0f, static_cast<float>(kOverlayNear), 100.0f);
    return view;
}

inline size_t pixelsOf(const RasterCanvas& canvas, Rgb colour) {
    size_t n = 0;
    for (uint32_t y = 0; y < canvas.height(); ++y) {
        for (uint32_t x = 0; x < canvas.width(); ++x)
            n += canvas.at(static_cast<int>(x), static_cast<int>(y)) == colour;
    }
    return n;
}

}  // namespace occsim::testing
