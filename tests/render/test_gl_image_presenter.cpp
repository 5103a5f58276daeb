// A CPU image shown in the default framebuffer (render/gl_image_presenter.h), as the viewer shows
// its pictures in the window.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "render/gl_api.h"
#include "render/gl_image_presenter.h"
#include "render_test_scene.h"

namespace occsim {
namespace {

TEST_P(RenderTest, APresentedImageFillsTheDefaultFramebuffer) {
    // The presenter draws into a window's default framebuffer; an EGL context made current
    // without a surface has none (headless runs render into framebuffer objects). OSMesa's client
    // buffer stands in for a window here, and tests/system/test_view_window.cpp runs the presenter
    // in a real one.
    if (GetParam() == Backend::Egl)
        GTEST_SKIP() << "a surfaceless EGL context has no default framebuffer";
    // Four quadrants of different colours, rows bottom-up.
    const uint32_t w = kW, h = kH;
    std::vector<uint8_t> image(size_t{w} * h * 4);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            uint8_t* p = &image[(size_t{y} * w + x) * 4];
            p[0] = x < w / 2 ? 200 : 10;
            p[1] = y < h / 2 ? 180 : 20;
            p[2] = 77;
            p[3] = 255;
        }
    }
    GlImagePresenter presenter;
    presenter.draw(image, w, h, w, h);
    glFinish();
    std::vector<uint8_t> shown(image.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadPixels(0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h), GL_RGBA, GL_UNSIGNED_BYTE,
                 shown.data());
    EXPECT_EQ(shown, image);
}

}  // namespace
}  // namespace occsim
