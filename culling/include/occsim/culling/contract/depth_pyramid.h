// The depth-pyramid capability of a RenderDevice (DeviceFeature kDepthPyramid): a hierarchical
// depth buffer built from what the device has drawn so far this frame, and a batch test of
// bounds against it. The two-phase hierarchical-Z culler (cullers/hzb_culler.h) is its user;
// render/gl_depth_pyramid.h implements it on the GPU, occsim/culling/testing/depth_raster_device.h
// in software over its raster.
//
// Semantics, the same for every device:
// - build() reduces the depth buffer as it is now (the draws of the frame so far) into a pyramid,
//   replacing the last one. Level 0 is the largest power of two no larger than the viewport on
//   each axis; each texel of every level holds the FARTHEST depth of all the pixels it covers
//   (geometry/hzb_rules.h states the coverage), so a bound nearer than some texel's value may
//   show, and one farther than every texel it touches is hidden by what was drawn.
// - testBounds() tests bounds (in the culling frame) against the last pyramid built and writes
//   one flag per bound: 1 when it may show a pixel, 0 when it is hidden. The level is the one at
//   which the bound's pixel footprint, rounded up, spans at most 2x2 texels, and every texel the
//   footprint touches is read (hzb_rules.h). A bound that reaches the near plane (or the eye
//   plane), or that the device cannot place on screen, is 1 without a test. It returns once the
//   flags are known (a GPU device reads them back here, once per call).
// - Before the first build() of a frame, or after a build() with nothing drawn, every bound
//   passes: an empty depth buffer hides nothing.
// Devices count builds and tested bounds in DeviceCounters (pyramid_builds, pyramid_bounds).
#pragma once

#include <cstdint>
#include <span>

#include "occsim/culling/geometry/aabb.h"

namespace occsim {

// The shape tested for each box handed to testBounds(): the box itself (its 8 corners projected)
// or the sphere around it (centre, half diagonal), whose projected rectangle is exact and cheaper
// to compute on a GPU, but larger.
enum class PyramidBound : uint8_t { Box, Sphere };

class DepthPyramid {
  public:
    virtual ~DepthPyramid() = default;

    virtual void build() = 0;
    // `visible` has one entry per box (visible.size() == boxes.size()).
    virtual void testBounds(std::span<const Aabb> boxes, PyramidBound shape,
                            std::span<uint8_t> visible) = 0;

    static constexpr uint32_t kNoLevel = UINT32_MAX;
    // The level testBounds() reads for this bound against the last pyramid built (rule 3), or
    // kNoLevel when it passes without a test (no pyramid, the near plane) or the device cannot
    // say. For decision logs (decision_log.h): asked outside the batch, only when someone records.
    virtual uint32_t levelOf(const Aabb&, PyramidBound) const { return kNoLevel; }
};

}  // namespace occsim
