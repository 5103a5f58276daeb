// Boxes drawn as wireframes through a frame's camera on a CPU picture, after the frame was
// measured (the renderer's buffers stay untouched): the viewer's node boxes and validation
// overlay, and the run's worst-window pictures. A box is in the culling frame, as the tree's
// bounds and the world boxes are.
#pragma once

#include "occsim/culling/geometry/aabb.h"
#include "render/gl_renderer.h"
#include "sim/output/raster_canvas.h"

namespace occsim {

// `box` as a wireframe through `view` (eye, rotation, projection), its edges clipped at the near
// plane `near_m`; a box that is not finite and ordered draws nothing.
void drawBoxWireframe(RasterCanvas& canvas, const ViewSetup& view, double near_m, const Aabb& box,
                      Rgb colour);

}  // namespace occsim
