// What the viewer shows, composed on the CPU after the frame was measured: the rendered colour
// buffer, then (each optional) the node boxes, the bird's-eye inset and the text panel. The same
// picture goes to the window and to screenshots, so a screenshot is exactly what was on screen.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sim/output/raster_canvas.h"
#include "sim/run/simulation.h"
#include "sim/view/hud.h"

namespace occsim {

struct ViewLayers {
    bool boxes = false;
    bool birds_eye = false;
    bool hud = true;
    // The validation overlay (validation_overlay.h): needs the frame measured against ground
    // truth (Simulation::objectVerdicts()) and, to tint missed objects' pixels, ground truth's IDs.
    bool validation = false;
    std::span<const uint32_t> truth_ids;
};

// `rgba` is the renderer's colour buffer (width * height, rows bottom-up). The boxes and the
// bird's-eye inset need the simulation's last frame traced (LiveControls::trace_every_frame);
// without a trace they are left out, as the validation overlay is without verdicts. `camera` is the
// scenario's (for the lens).
RasterCanvas composeViewPicture(std::span<const uint8_t> rgba, uint32_t width, uint32_t height,
                                const Simulation& sim, const CameraSpec& camera,
                                const ViewLayers& layers, const HudState& hud);

// An RGBA8 image with rows bottom-up as a canvas (rows top-down).
RasterCanvas canvasFromBottomUp(std::span<const uint8_t> rgba, uint32_t width, uint32_t height);

}  // namespace occsim
