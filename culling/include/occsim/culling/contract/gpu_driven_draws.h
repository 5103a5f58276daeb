// GPU-driven draws, an optional capability of a RenderDevice (DeviceFeature kGpuDrivenDraws;
// RenderDevice::gpuDrivenDraws() is nullptr on a device without it): the two-phase scheme of
// GPU-driven renderers (niagara, bevy, Unity 6, UE5) with every decision taken on the device and
// nothing read back during the frame. The culler hands over the frame's units (what is tested) and
// its draw list (what is drawn, each entry naming its unit); the device keeps each unit's
// visibility across frames itself, writes the draw commands of both phases and draws them with
// one multi-draw each. Only after the frame (outside its timing) does anyone learn what was drawn.
//
// Contract
// - drawFirstPhase(units): draws every entry of the draw list whose unit is `forced` (visible
//   without a test: the near plane reaches it) or whose slot passed the second phase of the
//   previous frame, at this frame's transforms. The slots are the device's: `slot_count` of them
//   (a unit's slot is below it), zero (not visible) when new, after resetVisibility(), and for the
//   `forgotten_slots` of this frame (forgotten before phase 1 reads them: a slot that now stands
//   for another unit, as a BSP node index the tree reused). The spans must stay valid until
//   drawSecondPhase() returns.
// - drawSecondPhase(test, shape): tests every unit that is not forced against the depth drawn so
//   far this frame, draws the entries whose unit passed and that the first phase did not draw,
//   and stores every unit's answer in its slot for the next frame (a forced unit passes).
//   GpuTest::Pyramid tests the unit's bound against a depth pyramid of that depth (the rules of
//   depth_pyramid.h and geometry/hzb_rules.h; `shape` box or sphere). GpuTest::BoxRaster
//   rasterises the unit's box, grown by the query-box pad (geometry/query_box.h), against the
//   depth buffer itself with early fragment tests and no writes, a unit passing when one fragment
//   of its box passes (GL_GEQUAL: a face coplanar with an occluder passes), as an occlusion query
//   would; the devices answer a box the near plane reaches as drawn passed without a test.
//   With `batch_ends` (GpuUnits), the units are tested and drawn in batches in that order: batch b
//   (units batch_ends[b-1] to batch_ends[b], the first from unit 0, the last ending at the last
//   unit) is tested against the depth of phase 1 and of every batch before it, and its survivors
//   drawn before the next batch is tested (a pyramid is rebuilt for each batch). Units listed
//   front to back, the near batches' draws hide what the far ones would pass on phase 1's depth
//   alone. Without, one batch.
// - readResults(first_phase, passed): after the frame, outside any timing: per unit, whether the
//   first phase drew its entries and whether the second phase passed it. The device's drawn set
//   and its counters (objects_drawn, triangles_drawn) count the entries drawn only once the host
//   has resolved the frame (a GL device reads its command lists back after the frame).
// - Nothing is read back from the device between drawFirstPhase() and the end of the frame:
//   DeviceCounters::read_backs counts every read-back a device makes during a frame, and stays 0
//   for these calls.
// - A device offers BoxRaster only when it can write a flag from a fragment (storage buffers in
//   the fragment stage): DeviceFeature kBoxRaster. Pyramid needs kDepthPyramid as well.
#pragma once

#include <cstdint>
#include <span>

#include "occsim/culling/contract/depth_pyramid.h"
#include "occsim/culling/geometry/aabb.h"

namespace occsim {

enum class GpuTest : uint8_t { Pyramid, BoxRaster };

// One frame's units and draw list. Units: bounds (the culling frame), slots and forced flags, one
// each per unit. Draw list: objects and the unit of each, one each per entry; an object appears in
// at most one entry, and the entries are listed in the order of their units (object_units does
// not decrease). batch_ends: phase 2's batches (above), increasing, the last one the unit count.
struct GpuUnits {
    std::span<const Aabb> bounds;
    std::span<const uint32_t> slots;
    std::span<const uint8_t> forced;
    std::span<const uint32_t> objects;
    std::span<const uint32_t> object_units;
    std::span<const uint32_t> batch_ends;
    std::span<const uint32_t> forgotten_slots;
    uint32_t slot_count = 0;
};

class GpuDrivenDraws {
  public:
    virtual ~GpuDrivenDraws() = default;

    // Forgets every slot's visibility (a new run or a camera cut the host knows of).
    virtual void resetVisibility() = 0;
    virtual void drawFirstPhase(const GpuUnits& units) = 0;
    virtual void drawSecondPhase(GpuTest test, PyramidBound shape) = 0;
    // Both spans have one entry per unit of the last frame.
    virtual void readResults(std::span<uint8_t> first_phase, std::span<uint8_t> passed) = 0;
    // Whether GpuTest::BoxRaster is offered (DeviceFeature kBoxRaster).
    virtual bool offersBoxRaster() const = 0;
};

}  // namespace occsim
