// See gl_shadow_map.h.
#include "render/gl_shadow_map.h"

#include <stdexcept>
#include <string>

#include "render/gl_api.h"

namespace occsim {

GlShadowMap::GlShadowMap(uint32_t size) : size_(size) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (size == 0 || size > static_cast<uint32_t>(max_size)) {
        throw std::runtime_error("a shadow map of " + std::to_string(size) +
                                 " texels a side: expected 1 to " + std::to_string(max_size) +
                                 " (this device's largest texture)");
    }
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, static_cast<GLsizei>(size),
                   static_cast<GLsizei>(size));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, texture_, 0);
    const GLenum none = GL_NONE;
    glDrawBuffers(1, &none);  // depth only: the draw program's colour and ID outputs go nowhere
    glReadBuffer(GL_NONE);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        glDeleteFramebuffers(1, &fbo_);
        glDeleteTextures(1, &texture_);
        throw std::runtime_error("the shadow map's framebuffer is incomplete (status " +
                                 std::to_string(status) + ")");
    }
    checkGl("shadow map set-up");
}

GlShadowMap::~GlShadowMap() {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &texture_);
}

void GlShadowMap::begin(GlRenderer& renderer) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, static_cast<GLsizei>(size_), static_cast<GLsizei>(size_));
    glDepthMask(GL_TRUE);
    const float far_value =
        renderer.depthConvention() == DepthConvention::ReverseFloat ? 0.0f : 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &far_value);
    renderer.forgetBoundState();  // the next draw binds the renderer's program and depth test
}

void GlShadowMap::readDepth(std::vector<float>& depth) const {
    depth.resize(size_t{size_} * size_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, static_cast<GLsizei>(size_), static_cast<GLsizei>(size_), GL_DEPTH_COMPONENT,
                 GL_FLOAT, depth.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

}  // namespace occsim
