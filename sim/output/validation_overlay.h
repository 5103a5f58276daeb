// The validation overlay: a frame's culling decisions against ground truth, over the rendered
// frame (the viewer's key v; the run's worst-window pictures). Missed objects (ground truth sees
// them, the culler did not draw them) in red: their ground-truth pixels tinted and their boxes
// drawn, so a hole shows where it is; objects drawn while hidden (over-draw) as yellow boxes;
// culled objects (not drawn, not seen) as dim grey boxes. Objects drawn and seen are left as
// rendered. Needs error measured (ground truth); composed on the CPU after the frame was
// measured, like the node boxes.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "occsim/culling/geometry/aabb.h"
#include "render/gl_renderer.h"
#include "sim/output/raster_canvas.h"
#include "sim/run/simulation.h"

namespace occsim {

inline constexpr Rgb kMissedColour{255, 40, 40};
inline constexpr Rgb kDrawnHiddenColour{255, 214, 40};
inline constexpr Rgb kCulledColour{120, 122, 128};

// The overlay's classes with their colours and legend labels, in drawing order (later on top).
struct ValidationClass {
    ObjectVerdict verdict;
    Rgb colour;
    std::string_view label;
};
std::span<const ValidationClass> validationClasses();

struct ValidationInput {
    std::span<const uint8_t> verdicts;   // Simulation::objectVerdicts(), one per object
    std::span<const Aabb> object_boxes;  // the world boxes (culling frame)
    // Ground truth's object IDs (index + 1, 0 background), width * height, rows bottom-up as the
    // renderer reads them; empty: no pixel is tinted.
    std::span<const uint32_t> truth_ids;
    ViewSetup view;  // the frame's camera
    double near_m = 0.1;
};

void drawValidationOverlay(RasterCanvas& canvas, const ValidationInput& in);

}  // namespace occsim
