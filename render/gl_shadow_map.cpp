// See gl_shadow_map.h.
#include "render/gl_shadow_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/gl_api.h"

namespace occsim {

GlShadowMap::GlShadowMap(uint32_t size, bool caster_ids) : size_(size) {
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
    if (caster_ids) {
        glGenTextures(1, &id_texture_);
        glBindTexture(GL_TEXTURE_2D, id_texture_);
        glTexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, static_cast<GLsizei>(size),
                       static_cast<GLsizei>(size));
        glBindTexture(GL_TEXTURE_2D, 0);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, id_texture_, 0);
        // The draw program's object-ID output (location 1) into the caster IDs; colour and
        // shadow texels go nowhere.
        const GLenum buffers[] = {GL_NONE, GL_COLOR_ATTACHMENT0};
        glDrawBuffers(2, buffers);
    } else {
        const GLenum none = GL_NONE;
        glDrawBuffers(1, &none);  // depth only: the draw program's outputs go nowhere
    }
    glReadBuffer(GL_NONE);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        glDeleteFramebuffers(1, &fbo_);
        glDeleteTextures(1, &texture_);
        if (id_texture_ != 0) glDeleteTextures(1, &id_texture_);
        throw std::runtime_error("the shadow map's framebuffer is incomplete (status " +
                                 std::to_string(status) + ")");
    }
    checkGl("shadow map set-up");
}

GlShadowMap::~GlShadowMap() {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &texture_);
    if (id_texture_ != 0) glDeleteTextures(1, &id_texture_);
}

void GlShadowMap::begin(GlRenderer& renderer) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, static_cast<GLsizei>(size_), static_cast<GLsizei>(size_));
    glDepthMask(GL_TRUE);
    const float far_value =
        renderer.depthConvention() == DepthConvention::ReverseFloat ? 0.0f : 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &far_value);
    if (id_texture_ != 0) {
        const GLuint no_caster[4] = {0, 0, 0, 0};
        glClearBufferuiv(GL_COLOR, 1, no_caster);
    }
    // The term would read the texture being written; setShadow() also makes the next draw bind
    // the renderer's program and depth test again.
    renderer.setShadow(nullptr);
}

ShadowLookup GlShadowMap::lookupFor(const ViewSetup& camera, const ViewSetup& light,
                                    DepthConvention depth) const {
    ShadowLookup lookup;
    lookup.texture = texture_;
    lookup.size = size_;
    lookup.view_to_light = cameraToLightClip(camera, light);
    // The light travels down its view's -z; in the camera's view space through both rotations.
    const glm::dmat3 light_to_world = glm::transpose(glm::dmat3(light.view_rotation));
    lookup.light_travel = glm::vec3(glm::dmat3(camera.view_rotation) * -light_to_world[2]);
    // Orthographic: x spans 2 / p[0][0] metres, y 2 / p[1][1]; stored depth changes by |p[2][2]|
    // a metre in reverse-Z (0..1 clip) and by |p[2][2]| / 2 in the conventional mapping.
    const glm::mat4& p = light.projection;
    lookup.texel_m = std::max(2.0f / p[0][0], 2.0f / p[1][1]) / static_cast<float>(size_);
    const float per_metre =
        depth == DepthConvention::ReverseFloat ? std::abs(p[2][2]) : 0.5f * std::abs(p[2][2]);
    lookup.depth_bias = lookup.texel_m * per_metre;
    return lookup;
}

void GlShadowMap::readDepth(std::vector<float>& depth) const {
    depth.resize(size_t{size_} * size_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, static_cast<GLsizei>(size_), static_cast<GLsizei>(size_), GL_DEPTH_COMPONENT,
                 GL_FLOAT, depth.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

void GlShadowMap::readCasterIds(std::vector<uint32_t>& ids) const {
    if (id_texture_ == 0) throw std::logic_error("GlShadowMap: made without caster IDs");
    ids.resize(size_t{size_} * size_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, static_cast<GLsizei>(size_), static_cast<GLsizei>(size_), GL_RED_INTEGER,
                 GL_UNSIGNED_INT, ids.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    checkGl("glReadPixels(caster IDs)");
}

}  // namespace occsim
