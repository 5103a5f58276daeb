#include "render/png_writer.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include <stdexcept>

namespace occsim {

std::vector<uint8_t> encodePngBottomUp(const std::vector<uint8_t>& rgba, uint32_t width,
                                       uint32_t height) {
    if (rgba.size() != size_t{width} * height * 4) {
        throw std::invalid_argument("encodePngBottomUp: image size does not match width*height*4");
    }
    std::vector<uint8_t> png;
    const int stride = static_cast<int>(width * 4);
    // Start at the last row and walk backwards with a negative stride: a vertical flip for free.
    const uint8_t* last_row = rgba.data() + size_t{height - 1} * width * 4;
    stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<uint8_t>*>(context);
            const auto* bytes = static_cast<const uint8_t*>(data);
            out->insert(out->end(), bytes, bytes + size);
        },
        &png, static_cast<int>(width), static_cast<int>(height), 4, last_row, -stride);
    if (png.empty()) throw std::runtime_error("PNG encoding failed");
    return png;
}

}  // namespace occsim
