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

// The replayed frame under a strip that says which frame it is, each frame pixel a square of
// errorPictureScale() as in the error pictures, so that a small frame can be seen.
std::vector<uint8_t> labelledFramePng(const ReplayedFrame& frame) {
    const int text_scale = 2, margin = 6;
    const int band = RasterCanvas::textHeight(text_scale) + 2 * margin;
    const std::string label = "frame " + std::to_string(frame.frame) + ", " +
                              fixed(frame.time_s, 3) + " s, as the camera saw it";
    const int scale = static_cast<int>(errorPictureScale(frame.width));
    const int w = static_cast<int>(frame.width) * scale, h = static_cast<int>(frame.height);
    RasterCanvas canvas(
        static_cast<uint32_t>(std::max(w, RasterCanvas::textWidth(label, text_scale) + 2 * margin)),
        static_cast<uint32_t>(band + h * scale), Rgb{255, 255, 255});
    canvas.text(margin, margin, label, Rgb{0, 0, 0}, text_scale);
    for (int y = 0; y < h; ++y) {
        // The frame's rows are bottom-up; the canvas's top-down.
        const uint8_t* row = frame.rgba.data() + static_cast<size_t>(h - 1 - y) * frame.width * 4;
        for (uint32_t x = 0; x < frame.width; ++x) {
            const uint8_t* c = row + 4 * x;
            const int x0 = static_cast<int>(x) * scale, y0 = band + y * scale;
            canvas.fillRect(x0, y0, x0 + scale - 1, y0 + scale - 1, Rgb{c[0], c[1], c[2]});
        }
    }
    return encodePngBottomUp(canvas.rgbaBottomUp(), canvas.width(), canvas.height());
}

}  // namespace

void PictureRecorder::onWindowFrame(const ReplayedFrame& frame) {
    const std::string name = windowPictureName(frame.frame);
    std::filesystem::create_directories(out_dir_);
    writeFileAtomically(out_dir_ / name, labelledFramePng(frame));
    windows_.push_back(name);
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
