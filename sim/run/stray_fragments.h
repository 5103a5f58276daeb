// Stray fragments: ground-truth pixels whose depth no point of their object can have.
//
// A rasteriser computes a fragment's depth from the plane through the triangle's vertices after
// snapping them to its subpixel grid. For a sliver seen almost edge-on that plane is so steep
// that a pixel centre the snapped triangle still covers can get a depth far outside the
// triangle's own range: llvmpipe drew one pixel of a teapot 7.2 to 9.2 m away at 3.7 m
// (general/dense-movers-near, frame 9), and GPUs are allowed to do the same (depth is clamped
// to the depth range, not to the primitive). No query box can see such a fragment, since it lies
// outside the box that bounds the object, so a conservative culler that leaves the object out
// is not wrong there; counting the pixel as error called CHC wrong on that frame.
//
// A fragment counts as stray when it is nearer than kStrayDepthMargin of the nearest view depth
// of its object's box (the box's nearest corner along the view axis): any point of the object
// lies at or beyond that depth, and the margin leaves every rounding of a legitimate fragment
// far inside (rounding moves a depth by a few parts in 10^7; the stray one was off by half).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "occsim/culling/geometry/aabb.h"
#include "render/gl_renderer.h"

namespace occsim {

inline constexpr double kStrayDepthMargin = 0.01;

// Per object, the nearest depth rank (GlRenderer::readDepthRanks) a fragment of it may store in
// `renderer`'s current view: boxes relative to view.box_origin, as the culler sees them.
void nearestLegitimateRanks(const GlRenderer& renderer, const ViewSetup& view,
                            std::span<const Aabb> boxes, std::vector<uint32_t>& out);

// Marks (1) each pixel whose object's fragment is nearer than that object's bound; returns how
// many. ids: object index + 1 (0: background, never stray).
int64_t markStrayFragments(std::span<const uint32_t> ids, std::span<const uint32_t> ranks,
                           std::span<const uint32_t> nearest_rank, std::vector<uint8_t>& stray);

}  // namespace occsim
