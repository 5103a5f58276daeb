// A RenderDevice with a known visibility function, for testing culling logic without OpenGL.
// It never renders anything; a query's result is the number of visible objects whose box overlaps
// any of the query's boxes (a stand-in for "samples passed"), so a query over a node's bounds is
// non-zero exactly when a visible object lies in (or overlaps) that node. Results become ready
// after a fixed number of later commands (draws or queries), like the deterministic latency mode
// of the GL device; taking one earlier counts as a wait. An answer is visible when its count is
// above 0.
//
// It offers conditional rendering (conditional_rendering.h) with a GPU's semantics on that
// answer: a conditional draw executes iff the answer is visible, or unconditionally under NoWait
// while the answer is not ready (fewer than `latency_commands` later commands). Executed draws
// join drawnObjects(), skipped ones skippedObjects(); both count as submitted draws.
// offerConditionalRendering(false) makes it a device without the capability.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/contract/render_device.h"
#include "occsim/culling/testing/command_latency_queries.h"

namespace occsim {

class ScriptedQueryDevice final : public RenderDevice, private ConditionalRendering {
  public:
    explicit ScriptedQueryDevice(uint32_t latency_commands = 0)
        : queries_(latency_commands, "ScriptedQueryDevice") {}

    // The current frame's truth: which objects are visible, and every object's box.
    void setVisibility(std::vector<uint8_t> visible, std::vector<Aabb> object_boxes);
    // The same, copied into the device's own buffers: a caller that changes the truth every frame
    // (a moving scene) allocates nothing once they are large enough.
    void updateVisibility(std::span<const uint8_t> visible, std::span<const Aabb> object_boxes);

    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override;
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override;
    bool isQueryReady(QueryId id) override;
    QueryAnswer takeAnswer(QueryId id) override;
    ConditionalRendering* conditionalRendering() override {
        return offer_conditional_ ? this : nullptr;
    }
    void offerConditionalRendering(bool offer) { offer_conditional_ = offer; }

    // What the culler did since the last clearLog().
    const std::vector<uint32_t>& drawnObjects() const { return drawn_; }
    // Conditional draws the device skipped (their query's answer was occluded).
    const std::vector<uint32_t>& skippedObjects() const { return skipped_; }
    const std::vector<Aabb>& queriedBoxes() const { return queried_; }
    // What each query since the last clearLog() was for (its first subject), in issue order.
    const std::vector<QueryTag>& queryTags() const { return tags_; }
    void clearLog();
    uint32_t pendingQueries() const { return queries_.pending(); }
    // The most queries that were ever in flight at once (issued, result not yet fetched).
    uint32_t maxPendingQueries() const { return max_pending_; }

  private:
    void drawIf(QueryId id, std::span<const uint32_t> objects, ConditionWait wait) override;
    void release(QueryId id) override { queries_.release(id); }

    CommandLatencyQueries queries_;
    bool offer_conditional_ = true;
    uint32_t max_pending_ = 0;
    std::vector<uint8_t> visible_;
    std::vector<Aabb> boxes_;
    std::vector<uint32_t> drawn_;
    std::vector<uint32_t> skipped_;
    std::vector<Aabb> queried_;
    std::vector<QueryTag> tags_;
};

}  // namespace occsim
