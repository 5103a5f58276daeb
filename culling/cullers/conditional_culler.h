// Conditional rendering (OpenGL 3.0, glBeginConditionalRender; issue 32): every object in the
// frustum (or, with node_queries, the objects a node stores itself) gets a query on its box and
// is drawn under that query's condition. Nothing is read back: the device decides whether the
// draws execute (on a GPU, the GPU; on llvmpipe, the CPU driver), so the culler never waits and
// its decisions do not depend on any answer. docs/conditional.md says what it costs where.
//
// The frame, front to back over the tree with frustum culling (traversal.h):
//   - an object whose box the near plane may cut (nearPlaneTouchesBox) is drawn unconditionally,
//     as every query culler draws such a box instead of querying it;
//   - every other object in the frustum is queried on its own box (with node_queries, a node's
//     such objects are queried together on the box around them, drawn unconditionally when that
//     box reaches the near plane), and the query is remembered;
//   - once more than `queries_ahead` queries wait for their draws, the oldest one's objects are
//     drawn under its condition (ConditionWait::Wait with `wait`, else NoWait) and the query is
//     released; at the end of the frame every remaining one is.
// Drawing under a query issued some queries earlier gives its answer time to arrive (NoWait
// draws unconditionally while it has not; Wait stalls the device on it), at the price of testing
// the box against a depth buffer that lacks the objects drawn in between. That stays
// conservative: depth only gets nearer during a frame, so a box that passed no samples then
// passes none at the end, and the object inside it cannot show.
//
// Needs the device's ConditionalRendering (CullerRow::device_needs): a run on a device
// without it refuses this culler before any work; cullAndRender() on such a device throws
// std::logic_error.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/contract/culler.h"
#include "occsim/culling/tree/traversal.h"

namespace occsim {

struct ConditionalOptions {
    bool wait = false;            // GL_QUERY_WAIT; false: GL_QUERY_NO_WAIT
    bool node_queries = false;    // one query per node's own objects; false: one per object
    uint32_t queries_ahead = 64;  // queries issued before the draws conditioned on the oldest
};

class ConditionalCuller final : public Culler {
  public:
    explicit ConditionalCuller(const ConditionalOptions& options = {}) : options_(options) {}
    void reset(const BspTree&) override {}
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

    const ConditionalOptions& options() const { return options_; }

  private:
    // A query and the objects drawn under it: objects_[first, first + count).
    struct Pending {
        QueryId query;
        uint32_t first;
        uint32_t count;
    };

    void queueQuery(const Aabb& box, QueryTag tag, std::span<const uint32_t> objects,
                    RenderDevice& device);
    void drawOldest(ConditionalRendering& conditional);

    ConditionalOptions options_;
    PreparedView view_;  // this frame's view with its plane table (prepareView)
    std::vector<NodeVisit> stack_;
    std::vector<uint32_t> batch_;    // a node's objects that are queried together
    std::vector<Pending> pending_;   // queried, not yet drawn; a FIFO from head_
    std::vector<uint32_t> objects_;  // the pending queries' objects
    size_t head_ = 0;
};

}  // namespace occsim
