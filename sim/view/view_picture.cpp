#include "sim/view/view_picture.h"

#include <algorithm>

#include "sim/output/birds_eye.h"
#include "sim/output/validation_overlay.h"
#include "sim/view/node_boxes.h"

namespace occsim {
namespace {

constexpr Rgb kInsetBorder{200, 200, 200};

// Pastes an RGBA8 image (rows bottom-up) with its top left at (x0, y0).
void paste(RasterCanvas& canvas, std::span<const uint8_t> rgba, uint32_t width, uint32_t height,
           int x0, int y0) {
    for (uint32_t y = 0; y < height; ++y) {
        const uint8_t* row = rgba.data() + size_t{height - 1 - y} * width * 4;
        for (uint32_t x = 0; x < width; ++x) {
            canvas.pixel(x0 + static_cast<int>(x), y0 + static_cast<int>(y),
                         {row[4 * x], row[4 * x + 1], row[4 * x + 2]});
        }
    }
}

// The bird's-eye picture of the traced frame in the bottom right corner, its longer side about
// 45% of the picture's shorter one.
void drawBirdsEyeInset(RasterCanvas& canvas, const Simulation& sim, const FrameTrace& trace,
                       std::span<const NodeClass> classes, const CameraSpec& camera) {
    const FrameView& view = sim.view();
    BirdsEyeInput in;
    in.tree = &sim.tree();
    in.object_boxes = sim.state().boxes;
    in.drawn_objects = trace.drawn_objects;
    in.node_classes = classes;
    in.view = view.cull;
    // The view rotation's third row is the backward axis in world space.
    const glm::mat4& r = view.render.view_rotation;
    in.forward = -glm::vec3(r[0][2], r[1][2], r[2][2]);
    in.fov_y_rad = static_cast<float>(glm::radians(camera.fov_y_deg));
    in.aspect = static_cast<float>(canvas.width()) / static_cast<float>(canvas.height());
    in.near_m = static_cast<float>(camera.near_m);
    in.far_m = static_cast<float>(camera.far_m);
    in.title.clear();        // the inset is too narrow for a title in the picture's large font
    in.draw_legend = false;  // the panel's legend explains the colours
    // Below about 120 pixels the picture's fixed margins leave no room for the scene.
    const uint32_t shorter = std::min(canvas.width(), canvas.height());
    const uint32_t long_side = std::min(std::max(120u, static_cast<uint32_t>(0.45 * shorter)),
                                        shorter > 16 ? shorter - 16 : shorter);
    const PictureSize size = birdsEyeSize(in, long_side);
    const std::vector<uint8_t> picture = renderBirdsEye(in, size.width, size.height);
    const int margin = 8;
    const int x0 = static_cast<int>(canvas.width()) - margin - static_cast<int>(size.width);
    const int y0 = static_cast<int>(canvas.height()) - margin - static_cast<int>(size.height);
    paste(canvas, picture, size.width, size.height, x0, y0);
    canvas.outlineRect(x0 - 1, y0 - 1, x0 + static_cast<int>(size.width),
                       y0 + static_cast<int>(size.height), kInsetBorder);
}

}  // namespace

RasterCanvas canvasFromBottomUp(std::span<const uint8_t> rgba, uint32_t width, uint32_t height) {
    RasterCanvas canvas(width, height, Rgb{});
    paste(canvas, rgba, width, height, 0, 0);
    return canvas;
}

RasterCanvas composeViewPicture(std::span<const uint8_t> rgba, uint32_t width, uint32_t height,
                                const Simulation& sim, const CameraSpec& camera,
                                const ViewLayers& layers, const HudState& hud) {
    RasterCanvas canvas = canvasFromBottomUp(rgba, width, height);
    if (layers.validation && sim.objectVerdicts().size() == sim.state().boxes.size()) {
        drawValidationOverlay(canvas, {sim.objectVerdicts(), sim.state().boxes, layers.truth_ids,
                                       sim.view().render, camera.near_m});
    }
    // Only a trace of the frame just rendered describes this picture.
    const FrameTrace* trace = sim.lastTrace();
    if (trace && trace->frame == sim.world().frame() && (layers.boxes || layers.birds_eye)) {
        const std::vector<NodeClass> classes = classifyNodes(sim.tree(), sim.view().cull, *trace);
        if (layers.boxes)
            drawNodeBoxes(canvas, sim.tree(), classes, sim.view().render, camera.near_m);
        if (layers.birds_eye) drawBirdsEyeInset(canvas, sim, *trace, classes, camera);
    }
    if (layers.hud) drawHud(canvas, hud);
    return canvas;
}

}  // namespace occsim
