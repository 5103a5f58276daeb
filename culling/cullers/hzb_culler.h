// Two-phase hierarchical-Z culling with the pyramid's flags read back (`hzb read_back=true`; the
// default `hzb` is GPU-driven: gpu_driven_culler.h), as GPU-driven renderers do it (zeux/niagara's
// early and late passes; nvpro-samples/gl_occlusion_culling's "temporal current frame"; bevy and
// Unity 6 use the same scheme): docs/hzb.md says how it works here, its sources and every
// deviation.
//
// Each frame, over the units in the frustum (objects, or BSP nodes: HzbOptions::node_units):
//   1. phase 1 draws the units that were visible last frame, at their current transforms, and
//      every unit whose bound reaches the near plane (visible without a test, rule 5 of
//      geometry/hzb_rules.h);
//   2. the device builds a depth pyramid from that depth buffer (DepthPyramid::build);
//   3. phase 2 tests every other unit in the frustum against the pyramid in one batch
//      (DepthPyramid::testBounds), draws those that pass and were not drawn in phase 1, and
//      rewrites every unit's visibility for the next frame: one drawn in phase 1 that the pyramid
//      now hides drops out.
// It is conservative whatever phase 1 drew: the pyramid holds only depths that are really in the
// frame, and a unit is hidden only behind them. Last frame's visible set (meaningless after a
// camera cut) decides only how much phase 2 has left to draw. With no phase-1 draw the pyramid
// would hide nothing, so it is not built and everything in the frustum is drawn.
//
// Needs the device's depth-pyramid capability (DeviceFeature kDepthPyramid); a device without it
// refuses this culler before any work (requireDeviceFeatures, occsim/culling/registry/registry.h).
// Called on such a device all the same, it draws everything in the frustum (frustum culling).
#pragma once

#include <cstdint>
#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/contract/depth_pyramid.h"
#include "occsim/culling/tree/node_state.h"
#include "occsim/culling/tree/traversal.h"

namespace occsim {

struct HzbOptions {
    // Test the sphere around each box instead of the box's 8 projected corners.
    bool sphere_bounds = false;
    // The tested units are BSP nodes (their subtree bounds; a node that passes draws the objects
    // stored in it) rather than objects. A node whose bound reaches the near plane hands its
    // objects down as units of their own.
    bool node_units = false;
    // The scheme as first built here: the culler reads the pyramid's flags back in the frame and
    // draws phase 2 itself (HzbCuller). Without it (the default) `hzb` is GPU-driven as engines
    // ship it (GpuDrivenCuller, gpu_driven_culler.h): the device decides and draws both phases
    // and nothing is read back in the frame; both draw the same objects frame by frame.
    bool read_back = false;
};

class HzbCuller final : public Culler {
  public:
    explicit HzbCuller(const HzbOptions& options = {});
    void reset(const BspTree& tree) override;
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

    const HzbOptions& options() const { return options_; }
    // The units tested against the pyramid in the last frame, and how many passed.
    uint32_t lastTested() const { return last_tested_; }
    uint32_t lastPassed() const { return last_passed_; }

  private:
    // A unit in the frustum this frame: an object, or a node with its inherited frustum flag.
    struct Unit {
        uint32_t index;
        bool is_node;
        bool inside_frustum;  // nodes: skip the objects' frustum tests
    };

    void collectUnits(const BspTree& tree, const CullFrame& frame);
    bool wasVisible(const Unit& u) const;
    void markVisible(const Unit& u);
    void drawUnit(const BspTree& tree, const Unit& u, RenderDevice& device);
    void drawObject(uint32_t object, RenderDevice& device);
    // Records `why` on the unit (an object, or a node's own objects) when someone records.
    void recordUnit(const Unit& u, Decision why) const;

    HzbOptions options_;
    PreparedView view_;
    std::vector<NodeVisit> stack_;
    // Stamps count calls of cullAndRender: visible in the previous call means stamp == pass_ - 1.
    std::vector<uint64_t> object_visible_;
    std::vector<uint64_t> object_drawn_;
    NodeStateArray<uint64_t> node_visible_;
    uint64_t pass_ = 0;
    // Per frame, reused.
    std::vector<Unit> units_;     // in the frustum, to be tested (front to back)
    std::vector<Aabb> boxes_;     // their bounds
    std::vector<uint8_t> flags_;  // the pyramid's answers
    uint32_t last_tested_ = 0, last_passed_ = 0;
};

}  // namespace occsim
