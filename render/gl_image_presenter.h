// Shows a CPU image in the default framebuffer of the current context (a window's back buffer):
// the RGBA8 pixels are uploaded to a texture, which is attached to a read framebuffer and blitted,
// scaled to the target size. No shaders and no state that the renderer relies on.
#pragma once

#include <cstdint>
#include <span>

namespace occsim {

class GlImagePresenter {
  public:
    GlImagePresenter();
    ~GlImagePresenter();
    GlImagePresenter(const GlImagePresenter&) = delete;
    GlImagePresenter& operator=(const GlImagePresenter&) = delete;

    // rgba: width * height * 4 bytes, row 0 at the bottom (as GL and RasterCanvas::rgbaBottomUp()
    // lay them out). Fills the default framebuffer's target_width x target_height pixels.
    void draw(std::span<const uint8_t> rgba, uint32_t width, uint32_t height, uint32_t target_width,
              uint32_t target_height);

  private:
    uint32_t texture_ = 0, framebuffer_ = 0;
};

}  // namespace occsim
