#include "sim/output/pictures.h"

#include <algorithm>
#include <cstdio>

#include "render/png_writer.h"
#include "sim/output/atomic_file.h"
#include "sim/output/birds_eye.h"
#include "sim/output/error_picture.h"
#include "sim/output/fixed_text.h"
#include "sim/output/moments.h"
#include "sim/output/raster_canvas.h"
#include "sim/output/validation_overlay.h"
#include "sim/world/camera_path.h"

namespace occsim {
namespace {

// The bird's-eye picture of the frame the simulation just rendered with tracing on.
std::vector<uint8_t> birdsEyePng(const Simulation& sim, const Scenario& scenario,
                                 const std::string& label) {
    const FrameTrace& trace = *sim.lastTrace();
    const std::vector<NodeClass> classes = classifyNodes(sim.tree(), sim.view().cull, trace);
    const CameraPose pose = sampleCameraPath(scenario.camera, trace.frame * scenario.dt_s);
    BirdsEyeInput in;
    in.tree = &sim.tree();
    in.object_boxes = sim.state().boxes;
    in.drawn_objects = trace.drawn_objects;
    in.node_classes = classes;
    in.view = sim.view().cull;
    in.forward = glm::vec3(glm::normalize(pose.target - pose.position));
    in.fov_y_rad = static_cast<float>(glm::radians(scenario.camera.fov_y_deg));
    in.aspect = static_cast<float>(scenario.width) / static_cast<float>(scenario.height);
    in.near_m = static_cast<float>(scenario.camera.near_m);
    in.far_m = static_cast<float>(scenario.camera.far_m);
    in.title = "frame " + std::to_string(trace.frame) + "  " + label;
    const PictureSize size = birdsEyeSize(in, 1000);
    return encodePngBottomUp(renderBirdsEye(in, size.width, size.height), size.width, size.height);
}

}  // namespace

RasterCanvas windowPicture(const ReplayedFrame& frame, const WindowVerdicts& window) {
    // The frame at its own size, rows top-down, with the overlay drawn at that size.
    RasterCanvas shot(frame.width, frame.height, Rgb{0, 0, 0});
    for (uint32_t y = 0; y < frame.height; ++y) {
        const uint8_t* row = frame.rgba.data() + size_t{frame.height - 1 - y} * frame.width * 4;
        for (uint32_t x = 0; x < frame.width; ++x) {
            const uint8_t* c = row + 4 * x;
            shot.pixel(static_cast<int>(x), static_cast<int>(y), Rgb{c[0], c[1], c[2]});
        }
    }
    std::string legend;
    if (window.verdicts) {
        // Every object drawn and seen but those the log names: the overlay draws no culled boxes
        // (the log keeps none), only what went wrong or was wasted.
        std::vector<uint8_t> verdicts(frame.object_boxes.size(),
                                      static_cast<uint8_t>(ObjectVerdict::DrawnVisible));
        for (uint32_t o : window.verdicts->missed) {
            if (o < verdicts.size()) verdicts[o] = static_cast<uint8_t>(ObjectVerdict::Missed);
        }
        for (uint32_t o : window.verdicts->drawn_hidden) {
            if (o < verdicts.size()) verdicts[o] = static_cast<uint8_t>(ObjectVerdict::DrawnHidden);
        }
        ValidationInput in;
        in.verdicts = verdicts;
        in.object_boxes = frame.object_boxes;
        in.truth_ids = frame.truth_ids;
        in.view = frame.view;
        in.near_m = frame.near_m;
        drawValidationOverlay(shot, in);
        legend = std::to_string(window.verdicts->missed.size()) + " missed (red), " +
                 std::to_string(window.verdicts->drawn_hidden.size()) +
                 " drawn while hidden (yellow)";
    } else {
        legend = window.measured ? "its decisions not kept: the run outgrew their log"
                                 : "no overlay: run with --error for its decisions";
    }

    const int text_scale = 2, margin = 6, line = RasterCanvas::textHeight(text_scale) + 4;
    const int band = 2 * line + 2 * margin;
    const std::string title = "frame " + std::to_string(frame.frame) + ", " +
                              fixed(frame.time_s, 3) + " s: worst window of " + window.label;
    const int scale = static_cast<int>(errorPictureScale(frame.width));
    const int w = static_cast<int>(frame.width) * scale, h = static_cast<int>(frame.height);
    const int text_width = std::max(RasterCanvas::textWidth(title, text_scale),
                                    RasterCanvas::textWidth(legend, text_scale));
    RasterCanvas canvas(static_cast<uint32_t>(std::max(w, text_width + 2 * margin)),
                        static_cast<uint32_t>(band + h * scale), Rgb{255, 255, 255});
    canvas.text(margin, margin, title, Rgb{0, 0, 0}, text_scale);
    canvas.text(margin, margin + line, legend, Rgb{0, 0, 0}, text_scale);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < static_cast<int>(frame.width); ++x) {
            const int x0 = x * scale, y0 = band + y * scale;
            canvas.fillRect(x0, y0, x0 + scale - 1, y0 + scale - 1, shot.at(x, y));
        }
    }
    return canvas;
}

void PictureRecorder::onWindowFrame(const ReplayedFrame& frame) {
    std::filesystem::create_directories(out_dir_);
    for (const WindowVerdicts& window : frame.windows) {
        const std::string name = windowPictureName(window.label, frame.frame);
        const RasterCanvas picture = windowPicture(frame, window);
        writeFileAtomically(out_dir_ / name, encodePngBottomUp(picture.rgbaBottomUp(),
                                                               picture.width(), picture.height()));
        windows_.push_back(name);
    }
}

PictureRecorder::PictureRecorder(std::filesystem::path out_dir,
                                 std::vector<uint32_t> capture_frames,
                                 std::optional<uint32_t> birds_eye_frame)
    : out_dir_(std::move(out_dir)),
      capture_frames_(std::move(capture_frames)),
      birds_eye_frame_(birds_eye_frame) {}

void PictureRecorder::onFrame(const FrameEvent& event) {
    if (event.repetition != 0) return;
    const std::string label = safeFileName(event.config.label);
    char name[200];
    if (birds_eye_frame_ == event.frame && event.simulation.lastTrace()) {
        std::snprintf(name, sizeof name, "birds-eye-%s-frame-%05u.png", label.c_str(), event.frame);
        std::filesystem::create_directories(out_dir_);
        writeFileAtomically(out_dir_ / name,
                            birdsEyePng(event.simulation, event.scenario, event.config.label));
        birds_eye_.push_back(name);
    }
    if (std::find(capture_frames_.begin(), capture_frames_.end(), event.frame) !=
        capture_frames_.end()) {
        event.renderer.readColor(rgba_);
        std::snprintf(name, sizeof name, "frame-%05u-%s.png", event.frame, label.c_str());
        std::filesystem::create_directories(out_dir_);
        writeFileAtomically(out_dir_ / name, encodePngBottomUp(rgba_, event.renderer.width(),
                                                               event.renderer.height()));
        captures_.push_back(name);
    }
}

}  // namespace occsim
