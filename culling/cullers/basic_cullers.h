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
    void reset(const BspTree&) override {}
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

  private:
    std::vector<NodeVisit> stack_;
    PreparedView view_;  // this frame's view with its plane table (prepareView)
};

// The limit of a culler that tests boxes (issue 42): every object ground truth saw is drawn first,
// which leaves the frame's final depth (the visible surfaces), then every other object in the
// frustum is queried by its box against that depth, all queries issued before any answer is
// taken, and those whose box shows a sample are drawn. What it draws beyond Ideal is what boxes
// cost; what a query culler draws beyond it is what scheduling costs. An oracle: its counts are
// the figure, its time (it waits for every answer) is not a culler's.
class IdealBoxCuller final : public Culler {
  public:
    void reset(const BspTree&) override {}
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

  private:
    std::vector<NodeVisit> stack_;
    PreparedView view_;
    std::vector<uint32_t> tested_;  // objects queried this frame, in issue order
    std::vector<QueryId> queries_;  // their queries
};

}  // namespace occsim
