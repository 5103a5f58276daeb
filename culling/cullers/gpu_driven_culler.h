// GPU-driven two-phase culling, as GPU-driven renderers ship it (zeux/niagara, bevy, Unity 6,
// UE5's instance culling; nvpro-samples/gl_occlusion_culling's "raster" and "hiz" modes): the
// culler only says what the frame's units are; the device decides and draws both phases from its
// own buffers (occsim/culling/contract/gpu_driven_draws.h) and reads nothing back in the frame.
// docs/hzb.md says how the two phases work here, their sources and every deviation; with
// GpuTest::Pyramid this culler draws, frame by frame, what the read-back HzbCuller draws
// (GpuDrivenCuller.NeverCullsAnObjectTheExactDepthBufferSees), GpuTest::BoxRaster is
// nvpro-samples/gl_occlusion_culling's "raster" mode.
//
// Each frame, over the units in the frustum (objects, or BSP nodes with node_units):
//   1. the culler lists every unit (its bound, its slot of device-side visibility, whether the
//      near plane reaches it: rule 5 of geometry/hzb_rules.h, visible without a test) and every
//      object to draw with its unit; the device draws the units that passed last frame and the
//      forced ones, at their current transforms;
//   2. the device tests every other unit against that depth (a pyramid of it, or each unit's
//      box rasterised against it), draws those that pass and were not drawn in phase 1, and keeps
//      every unit's answer for the next frame.
// Conservative whatever phase 1 drew, as hzb_culler.h says: the depth tested against holds only
// what is really in the frame. After the frame (afterFrame) the culler reads the device's
// per-unit answers, only when someone records its reasons.
//
// Needs the device's GPU-driven draws (DeviceFeature kGpuDrivenDraws; and kDepthPyramid for the
// pyramid, kBoxRaster for boxes): a run on a device without them is refused before frame 0.
// Called on such a device all the same, it draws everything in the frustum (frustum culling).
#pragma once

#include <cstdint>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/contract/gpu_driven_draws.h"
#include "occsim/culling/tree/traversal.h"

namespace occsim {

struct GpuDrivenOptions {
    GpuTest test = GpuTest::Pyramid;
    PyramidBound shape = PyramidBound::Box;  // Pyramid only: the box's corners or its sphere
    // The tested units are BSP nodes (their subtree bounds; a node that passes draws the objects
    // stored in it) rather than objects. A node whose bound reaches the near plane hands its
    // objects down as units of their own.
    bool node_units = false;
    // Phase 2 in this many batches, front to back, each twice the units of the one before
    // (secondPhaseBatchEnds): a batch is tested against the depth of phase 1 and of the batches
    // before it. 1 is the two phases as published.
    uint32_t batches = 1;
};

// The ends of `batches` batches over `units` units, each twice the size of the one before (the
// last takes what rounding leaves), so that the first, nearest batches are small: what they draw
// hides the many far units of the last. Empty batches are dropped; `ends` ends at `units`.
void secondPhaseBatchEnds(uint32_t units, uint32_t batches, std::vector<uint32_t>& ends);

class GpuDrivenCuller final : public Culler {
  public:
    explicit GpuDrivenCuller(const GpuDrivenOptions& options);
    void reset(const BspTree& tree) override;
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;
    void afterFrame(RenderDevice& device) override;

    const GpuDrivenOptions& options() const { return options_; }
    // The last frame's units (0 when the device had no GPU-driven draws): tests of the rules.
    uint32_t lastUnits() const { return static_cast<uint32_t>(bounds_.size()); }
    // The slots the last frame forgot (node_units: nodes whose index the tree reused).
    const std::vector<uint32_t>& lastForgottenSlots() const { return forgotten_slots_; }

  private:
    void collectUnits(const BspTree& tree, const CullFrame& frame);
    void addUnit(const Aabb& bound, uint32_t slot, bool forced, QueryTag tag);
    void drawEverythingInFrustum(const BspTree& tree, RenderDevice& device);
    void forgetReusedNodes(const BspTree& tree);

    GpuDrivenOptions options_;
    PreparedView view_;
    std::vector<NodeVisit> stack_;
    bool reset_device_ = true;  // the device's slots still hold another run's visibility
    bool used_device_ = false;  // this frame went through the device's GPU-driven draws
    uint32_t object_count_ = 0;
    // This frame's units and draw list (GpuUnits' spans point here), reused.
    std::vector<Aabb> bounds_;
    std::vector<uint32_t> slots_;
    std::vector<uint8_t> forced_;
    std::vector<QueryTag> tags_;  // per unit, what it stands for in the decision log
    std::vector<uint32_t> objects_, object_units_;
    std::vector<uint32_t> batch_ends_;
    // With node_units: each node's generation when its slot last stood for it, and the slots of
    // nodes whose index the tree has reused since (BspNode::generation), forgotten this frame.
    std::vector<uint32_t> node_generation_;
    uint64_t structure_version_ = 0;
    std::vector<uint32_t> forgotten_slots_;
    std::vector<uint8_t> first_phase_, passed_;
};

}  // namespace occsim
