#include "sim/output/error_picture.h"

#include <algorithm>
#include <stdexcept>

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

}  // namespace occsim
