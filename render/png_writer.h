// PNG encoding of RGBA8 images (bytes in memory; callers write files atomically).
#pragma once

#include <cstdint>
#include <vector>

namespace occsim {

// rgba: width*height*4 bytes, row 0 at the bottom (as glReadPixels returns it); the PNG is written
// top row first so that it looks upright.
std::vector<uint8_t> encodePngBottomUp(const std::vector<uint8_t>& rgba, uint32_t width,
                                       uint32_t height);

}  // namespace occsim
