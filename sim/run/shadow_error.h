// How a culled frame's shadow term differs from ground truth's (docs/views.md), from both
// renders' object IDs and shadow texels (GlRenderer::readShadowTexels) and which casters each
// shadow pass drew. Where a pixel shows the same object in both renders, the same fragment is
// shaded from the same light view, so its lit or shadowed state differs only where the two
// shadow maps differ at its texel: a caster ground truth has there was left out. Where the
// object differs, the pixel is the camera view's error or tie (pixel_error.h), counted there.
#pragma once

#include <cstdint>
#include <span>

#include "sim/run/pixel_error.h"

namespace occsim {

struct ShadowPixelCounts {
    int64_t error = 0;
    int64_t tie = 0;
};

// Pixels showing the same object (ID non-zero) in both renders, lit in one and shadowed in the
// other: an error, or a tie where the two shadow maps' depths at the pixel's texel (the one that
// shadows it in whichever render it is shadowed) lie within kDepthTieSteps of each other (as
// float ranks: the maps hold 32-bit floats in [0, 1] in both conventions). A tie is the same
// surface a step away, another caster where ground truth's was left out: the shadow is the same
// but for a receiver within that step of the bias. Without maps (empty spans) every difference
// is an error: the caller reads the maps back only on a frame with a difference. The ID and
// texel spans are the same size; the maps, when given, hold every texel the texels name.
ShadowPixelCounts compareShadowTerms(std::span<const uint32_t> truth_ids,
                                     std::span<const uint32_t> truth_texels,
                                     std::span<const uint32_t> culled_ids,
                                     std::span<const uint32_t> culled_texels,
                                     std::span<const float> truth_map = {},
                                     std::span<const float> culled_map = {});

// Casters whose shadow ground truth shows on a visible pixel (GroundTruthFrame::shadow_pixels > 0)
// that the culled shadow pass did not draw (`drawn`, per object; shorter: the rest not drawn).
int64_t countMissedCasters(std::span<const uint32_t> shadow_pixels, std::span<const uint8_t> drawn);

}  // namespace occsim
