// A picture of a frame that went wrong: the culled frame, ground truth, and the differences
// marked, side by side, for a person to look at when a regression fails.
#pragma once

#include "sim/run/simulation.h"

#include <cstdint>
#include <vector>

namespace occsim {

// RGBA8, (3 * width) x height, rows bottom-up (encode with encodePngBottomUp): culled | ground
// truth | ground truth dimmed with every pixel whose object ID differs in magenta.
std::vector<uint8_t> composeErrorPicture(const ErrorFrame& frame, uint32_t width, uint32_t height);

}  // namespace occsim
