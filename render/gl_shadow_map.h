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
    // With caster IDs (ground truth): a second texture holds, per texel, the ID (object + 1) of
    // the caster nearest the light there, 0 where none is.
    explicit GlShadowMap(uint32_t size, bool caster_ids = false);
    ~GlShadowMap();
    GlShadowMap(const GlShadowMap&) = delete;
    GlShadowMap& operator=(const GlShadowMap&) = delete;

    uint32_t size() const { return size_; }
    uint32_t depthTexture() const { return texture_; }

    // Binds the map's framebuffer and viewport, clears its depth to the far value of the
    // renderer's convention (and its caster IDs to 0) and turns the renderer's shadow term off;
    // the renderer's draws go into it until its next beginFrame().
    void begin(GlRenderer& renderer);

    // How a camera pass looks this map up (GlRenderer::setShadow) when it was rendered with
    // `light`'s orthographic projection (makeLightRenderView) and the camera is `camera`: a
    // texel's width from the projection's extent, a depth bias of one texel's width in depth.
    ShadowLookup lookupFor(const ViewSetup& camera, const ViewSetup& light,
                           DepthConvention depth) const;

    // The stored depths, row 0 at the bottom (tests, pictures).
    void readDepth(std::vector<float>& depth) const;
    // The caster IDs, row 0 at the bottom; std::logic_error for a map made without them.
    void readCasterIds(std::vector<uint32_t>& ids) const;

  private:
    uint32_t size_ = 0;
    uint32_t texture_ = 0, fbo_ = 0;
    uint32_t id_texture_ = 0;  // 0: no caster IDs
};

}  // namespace occsim
