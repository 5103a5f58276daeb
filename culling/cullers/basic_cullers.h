// The reference cullers: frustum culling only (VFC, also the ground-truth renderer), hierarchical
// stop-and-wait occlusion queries, and the Ideal oracle.
#pragma once

#include <vector>

#include "occsim/culling/contract/culler.h"
#include "occsim/culling/tree/traversal.h"

namespace occsim {

// Draws every object whose box passes the frustum, in front-to-back tree order.
class VfcCuller final : public Culler {
  public:
    std::string_view name() const override { return "vfc"; }
    void reset(const BspTree&) override {}
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

  private:
    std::vector<NodeVisit> stack_;
    PreparedView view_;  // this frame's view with its plane table (prepareView)
};

// Front to back; each node that passes the frustum is queried and its result awaited before the
// traversal goes on (the "simple OC" of Kovalčík & Sochor). Nodes the near plane may cut are
// rendered without a query.
class StopAndWaitCuller final : public Culler {
  public:
    std::string_view name() const override { return "stop-and-wait"; }
    void reset(const BspTree&) override {}
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

  private:
    std::vector<NodeVisit> stack_;
    PreparedView view_;  // this frame's view with its plane table (prepareView)
};

// Draws exactly the objects the ground-truth render of this frame saw, with no queries: the
// lower bound of what any culler can draw.
class IdealCuller final : public Culler {
  public:
    std::string_view name() const override { return "ideal"; }
    void reset(const BspTree&) override {}
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

  private:
    std::vector<NodeVisit> stack_;
    PreparedView view_;  // this frame's view with its plane table (prepareView)
};

}  // namespace occsim
