// The BSP nodes' bounding boxes drawn over the rendered frame, each in the colour of what the
// culler did with the node this frame (the classes of sim/output/birds_eye.h, in the same colours
// as the bird's-eye picture). Drawn as wireframes through the frame's own camera, after the frame
// was measured, on the CPU image that the viewer shows: the renderer's buffers stay untouched.
#pragma once

#include <span>
#include <string_view>

#include "occsim/culling/tree/bsp_tree.h"
#include "render/gl_renderer.h"
#include "sim/output/birds_eye.h"
#include "sim/output/raster_canvas.h"

namespace occsim {

// The classes shown in the view, with their legend labels, in drawing order (later on top).
struct NodeBoxClass {
    NodeClass node_class;
    std::string_view label;
};
std::span<const NodeBoxClass> shownNodeBoxClasses();

// Draws the box of every node whose class is shown. `view` is the frame's camera (eye,
// rotation, reverse-Z projection); edges in front of the near plane are clipped to it.
void drawNodeBoxes(RasterCanvas& canvas, const BspTree& tree, std::span<const NodeClass> classes,
                   const ViewSetup& view, double near_m);

}  // namespace occsim
