#include "sim/output/error_picture.h"

#include <algorithm>
#include <stdexcept>

#include "sim/output/raster_canvas.h"

namespace occsim {

std::vector<uint8_t> composeErrorPicture(const ErrorFrame& frame, uint32_t width, uint32_t height) {
    const size_t pixels = size_t{width} * height;
    if (frame.culled_rgba.size() != pixels * 4 || frame.truth_rgba.size() != pixels * 4 ||
        frame.culled_ids.size() != pixels || frame.truth_ids.size() != pixels ||
        frame.differences.size() != pixels) {
        throw std::invalid_argument("composeErrorPicture: buffers do not match the frame size");
    }
    const size_t row_out = size_t{width} * 3 * 4;
    std::vector<uint8_t> out(row_out * height);
    for (uint32_t y = 0; y < height; ++y) {
        uint8_t* row = out.data() + y * row_out;
        const size_t in = size_t{y} * width * 4;
        std::copy_n(frame.culled_rgba.data() + in, width * 4, row);
        std::copy_n(frame.truth_rgba.data() + in, width * 4, row + width * 4);
        uint8_t* diff = row + 2 * width * 4;
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t{y} * width + x;
            uint8_t* p = diff + x * 4;
            const auto difference = static_cast<PixelDifference>(frame.differences[i]);
            if (difference == PixelDifference::Error) {
                p[0] = kErrorColour[0], p[1] = kErrorColour[1], p[2] = kErrorColour[2];
            } else if (difference == PixelDifference::Tie) {
                p[0] = kTieColour[0], p[1] = kTieColour[1], p[2] = kTieColour[2];
            } else if (difference == PixelDifference::Stray) {
                p[0] = kStrayColour[0], p[1] = kStrayColour[1], p[2] = kStrayColour[2];
            } else {
                for (int c = 0; c < 3; ++c) p[c] = frame.truth_rgba[i * 4 + c] / 3;
            }
            p[3] = 255;
        }
    }
    return out;
}

uint32_t errorPictureScale(uint32_t frame_width) {
    return std::clamp<uint32_t>(800 / std::max<uint32_t>(frame_width, 1), 1, 8);
}

LabelledPicture labelledErrorPicture(const ErrorFrame& frame, uint32_t width, uint32_t height,
                                     const std::string& algorithm) {
    const std::vector<uint8_t> panels = composeErrorPicture(frame, width, height);
    const uint32_t scale = errorPictureScale(width);
    const int text_scale = 2, margin = 6;
    const int band = RasterCanvas::textHeight(text_scale) + 2 * margin;  // a label's strip
    const int panel_w = static_cast<int>(width * scale), panel_h = static_cast<int>(height * scale);
    const std::string labels[3] = {
        "culled: " + algorithm + ", frame " + std::to_string(frame.frame), "ground truth",
        "difference: " + std::to_string(frame.error_pixels) + " error px (magenta), " +
            std::to_string(frame.tie_pixels) + " tie px (yellow), stray (cyan)"};
    const int label_w = RasterCanvas::textWidth(labels[2], text_scale) + 2 * margin;
    RasterCanvas canvas(static_cast<uint32_t>(std::max(panel_w, label_w)),
                        static_cast<uint32_t>(3 * (band + panel_h)), Rgb{255, 255, 255});
    const size_t row_in = size_t{width} * 3 * 4;
    for (int p = 0; p < 3; ++p) {
        const int top = p * (band + panel_h);
        canvas.text(margin, top + margin, labels[p], Rgb{0, 0, 0}, text_scale);
        // The panels' rows are bottom-up; the canvas's top-down.
        for (uint32_t y = 0; y < height; ++y) {
            const uint8_t* row =
                panels.data() + (height - 1 - y) * row_in + static_cast<size_t>(p) * width * 4;
            for (uint32_t x = 0; x < width; ++x) {
                const uint8_t* c = row + x * 4;
                const int x0 = static_cast<int>(x * scale),
                          y0 = top + band + static_cast<int>(y * scale);
                canvas.fillRect(x0, y0, x0 + static_cast<int>(scale) - 1,
                                y0 + static_cast<int>(scale) - 1, Rgb{c[0], c[1], c[2]});
            }
        }
    }
    return {canvas.width(), canvas.height(), canvas.rgbaBottomUp()};
}

}  // namespace occsim
