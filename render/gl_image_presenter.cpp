#include "render/gl_image_presenter.h"

#include <stdexcept>

#include "render/gl_api.h"

namespace occsim {

GlImagePresenter::GlImagePresenter() {
    glGenTextures(1, &texture_);
    glGenFramebuffers(1, &framebuffer_);
    checkGl("image presenter set-up");
}

GlImagePresenter::~GlImagePresenter() {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &texture_);
}

void GlImagePresenter::draw(std::span<const uint8_t> rgba, uint32_t width, uint32_t height,
                            uint32_t target_width, uint32_t target_height) {
    if (rgba.size() != size_t{width} * height * 4) {
        throw std::invalid_argument(
            "image presenter: the image is not width x height RGBA8 pixels");
    }
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, static_cast<GLsizei>(width),
                 static_cast<GLsizei>(height), 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    // Same size: a plain copy; otherwise linear scaling (a window mid-resize).
    const GLenum filter =
        (width == target_width && height == target_height) ? GL_NEAREST : GL_LINEAR;
    glBlitFramebuffer(0, 0, static_cast<GLint>(width), static_cast<GLint>(height), 0, 0,
                      static_cast<GLint>(target_width), static_cast<GLint>(target_height),
                      GL_COLOR_BUFFER_BIT, filter);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    checkGl("image presenter blit");
}

}  // namespace occsim
