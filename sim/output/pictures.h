// Pictures taken while a benchmark runs, between frames and outside every timing: PNG captures of
// chosen frames' colour buffers and bird's-eye pictures of one frame's culling decisions. Plug
// onFrame() into BenchOptions::on_frame; every file is written atomically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/output/raster_canvas.h"
#include "sim/run/runner.h"

namespace occsim {

// A configuration's worst window's worst frame as a picture: a strip that says which frame,
// whose window and what the colours mean, over the frame as the camera saw it (each frame pixel a
// square of errorPictureScale()), with the configuration's verdicts of that frame as the
// validation overlay (validation_overlay.h: missed objects tinted red with red boxes, objects
// drawn while hidden as yellow boxes); without verdicts, the frame alone and the strip says why.
RasterCanvas windowPicture(const ReplayedFrame& frame, const WindowVerdicts& window);

class PictureRecorder {
  public:
    // capture_frames: frames whose culled colour buffer is saved (frame-NNNNN-<config>.png);
    // birds_eye_frame: the frame pictured from above (birds-eye-<config>-frame-NNNNN.png), which
    // must also be BenchOptions::trace_frame. First repetition only.
    PictureRecorder(std::filesystem::path out_dir, std::vector<uint32_t> capture_frames,
                    std::optional<uint32_t> birds_eye_frame);

    void onFrame(const FrameEvent& event);
    // A worst window's worst frame, replayed after the run (BenchOptions::on_window_frame): per
    // configuration whose worst window it ends, windowPictureName() (windowPicture()).
    void onWindowFrame(const ReplayedFrame& frame);

    const std::vector<std::string>& captureFiles() const { return captures_; }
    const std::vector<std::string>& birdsEyeFiles() const { return birds_eye_; }
    const std::vector<std::string>& windowFiles() const { return windows_; }

  private:
    std::filesystem::path out_dir_;
    std::vector<uint32_t> capture_frames_;
    std::optional<uint32_t> birds_eye_frame_;
    std::vector<std::string> captures_, birds_eye_, windows_;
    std::vector<uint8_t> rgba_;  // read-back scratch
};

}  // namespace occsim
