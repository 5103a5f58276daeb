// The receivers of receiver-masked caster culling (sim/world/receiver_mask.h, docs/views.md):
// the points the camera's pass left in its depth buffer, each pixel's centre unprojected from its
// stored depth into the world, laid into the mask with a margin.
#pragma once

#include <cstdint>
#include <span>

#include "render/gl_renderer.h"
#include "sim/world/receiver_mask.h"

namespace occsim {

// `depth_ranks` as GlRenderer::readDepthRanks gives them (width * height, row 0 at the bottom,
// rank 0 the cleared background, which is no receiver) for `camera`'s view in `depth`'s
// convention. Each pixel's point goes into `mask` grown by `margin_m` and by how far its stored
// depth's neighbouring values lie from it (what the depth buffer rounds away: centimetres far
// off in a 24-bit buffer).
void addVisibleReceivers(std::span<const uint32_t> depth_ranks, uint32_t width, uint32_t height,
                         const ViewSetup& camera, DepthConvention depth, double margin_m,
                         ReceiverMask& mask);

}  // namespace occsim
