// A light's shadow map (docs/views.md): a square depth texture, in the renderer's depth
// convention, and the framebuffer that renders the shadow casters into it, depth only, with the
// renderer's own meshes and draw program. A frame renders its shadow passes first:
//   renderer.setView(light_view, light_model_views);  shadow.begin(renderer);
//   renderer.drawObject(caster) ...;
// then the camera's setView() and beginFrame(), which binds the renderer's framebuffer again.
// Needs a current GlContext.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "render/gl_renderer.h"

namespace occsim {

class GlShadowMap {
  public:
    // A map `size` texels a side; std::runtime_error beyond the context's GL_MAX_TEXTURE_SIZE
    // (a run checks that before frame 0: sim/run/light_limits.h).
    explicit GlShadowMap(uint32_t size);
    ~GlShadowMap();
    GlShadowMap(const GlShadowMap&) = delete;
    GlShadowMap& operator=(const GlShadowMap&) = delete;

    uint32_t size() const { return size_; }
    uint32_t depthTexture() const { return texture_; }

    // Binds the map's framebuffer and viewport and clears its depth to the far value of the
    // renderer's convention; the renderer's draws go into it until its next beginFrame().
    void begin(GlRenderer& renderer);

    // The stored depths, row 0 at the bottom (tests, pictures).
    void readDepth(std::vector<float>& depth) const;

  private:
    uint32_t size_ = 0;
    uint32_t texture_ = 0, fbo_ = 0;
};

}  // namespace occsim
