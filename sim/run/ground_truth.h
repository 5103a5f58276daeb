// Ground truth of a shared world's frame: every object drawn into the object-ID and depth
// buffers (no culling code on the way: the GPU clips) and both read back, and with a shadow view
// every object drawn into the light's shadow map first and the camera's pass shaded from it, at
// most once per frame however many configurations ask, outside every frame timing, with a count and
// the time it cost, so a run can show that it rendered none when no error was asked for.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "render/gl_query_device.h"
#include "render/gl_renderer.h"
#include "render/gl_shadow_map.h"
#include "sim/run/shared_world.h"

namespace occsim {

struct GroundTruthFrame {
    std::vector<uint32_t> ids;     // width * height, object index + 1, 0 = background
    std::vector<uint32_t> depth;   // width * height, GlRenderer::readDepthRanks (nearer is larger)
    std::vector<uint8_t> stray;    // width * height, 1: a stray fragment (stray_fragments.h)
    int64_t stray_fragments = 0;   // pixels marked in `stray`
    std::vector<uint8_t> visible;  // per object: at least one pixel that is not stray
    // Stereo (SharedWorld::stereoViews): per object, bit 0 set when the left eye sees it (a pixel
    // that is not stray in its half), bit 1 the right eye; empty without stereo.
    std::vector<uint8_t> eye_visible;
    std::vector<uint8_t> rgba;  // colour, only when asked for
    // With a shadow pass this frame (SharedWorld::shadowView, docs/views.md): every object drawn
    // into the light's shadow map, the camera's pass shaded from it.
    bool has_shadow = false;
    std::vector<uint32_t> shadow_texels;   // width * height, GlRenderer::readShadowTexels
    std::vector<uint32_t> shadow_casters;  // per map texel, the nearest caster's ID (0: none)
    // Per object: the visible pixels (not stray) its shadow falls on, as the caster nearest the
    // light in the texel that shadows each; a caster whose shadow shows has at least one.
    std::vector<uint32_t> shadow_pixels;
};

class GroundTruth {
  public:
    explicit GroundTruth(GlRenderer& renderer);

    // The current frame of `world`, rendered on the first call for that frame and kept for the
    // others. with_colour also reads the colour buffer; when an earlier call for the frame did
    // not, the frame is rendered again (the framebuffer has been drawn over since).
    const GroundTruthFrame& of(const SharedWorld& world, bool with_colour = false);

    // The depth of the last frame's shadow map (row 0 at the bottom), read back on demand: until
    // the next frame is rendered. std::logic_error when that frame had no shadow pass.
    void readShadowDepth(std::vector<float>& depth) const;

    uint32_t renders() const { return renders_; }
    double msTotal() const { return ms_total_; }  // render and read-back, wall clock

  private:
    GlRenderer& renderer_;
    GlQueryDevice device_;
    GroundTruthFrame frame_;
    std::unique_ptr<GlShadowMap> shadow_map_;  // with caster IDs, made on the first shadow pass
    std::vector<uint32_t> nearest_rank_;       // per object, this frame (nearestLegitimateRanks)
    uint64_t serial_ = 0;                      // SharedWorld::frameSerial() of frame_; 0: none yet
    bool has_colour_ = false;
    uint32_t renders_ = 0;
    double ms_total_ = 0.0;
};

}  // namespace occsim
