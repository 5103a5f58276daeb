// A picture of a frame that went wrong: the culled frame, ground truth, and the differences
// marked (errors apart from ties), side by side, for a person to look at when a regression fails.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/run/simulation.h"

namespace occsim {

// Error pixels in magenta; tie pixels (another object at the same depth: no error) in yellow;
// stray pixels (a fragment of ground truth's nearer than its object: no error) in cyan.
inline constexpr uint8_t kErrorColour[3] = {255, 0, 255};
inline constexpr uint8_t kTieColour[3] = {255, 210, 0};
inline constexpr uint8_t kStrayColour[3] = {0, 220, 255};

// RGBA8, (3 * width) x height, rows bottom-up (encode with encodePngBottomUp): culled | ground
// truth | ground truth dimmed with every error pixel in magenta, every tie pixel in yellow, every
// stray one in cyan.
std::vector<uint8_t> composeErrorPicture(const ErrorFrame& frame, uint32_t width, uint32_t height);

// How many picture pixels per frame pixel: a whole factor that brings a panel to about 800
// pixels wide (a 200 x 150 frame: 4), so that a single error pixel is a square one can see; 1 to
// 8.
uint32_t errorPictureScale(uint32_t frame_width);

// The worst-frame picture report.md shows: the three panels of composeErrorPicture() one above
// the other, each scaled up by errorPictureScale() and under its label (the culled frame with the
// algorithm and frame, ground truth, the difference with its counts and colours).
struct LabelledPicture {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;  // RGBA8, rows bottom-up (encodePngBottomUp)
};
LabelledPicture labelledErrorPicture(const ErrorFrame& frame, uint32_t width, uint32_t height,
                                     const std::string& algorithm);

}  // namespace occsim
