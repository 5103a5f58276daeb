// RenderDevice over real OpenGL occlusion queries (GL_SAMPLES_PASSED). Query objects come from a
// pool that grows as needed and is reused; an id stays valid across frames until its result is
// fetched. Draw and query submission time and blocked time are measured here, so cullers need not.
// An answer is polled only until it is known to be ready: the device remembers that, so asking
// again, or taking the answer, asks the driver nothing more than the result itself. Ids handed
// back are checked (query_id_check.h: in debug builds a dead id aborts with a message; in every
// build a dead id is never released twice), and so is every GL call here in debug builds
// (gl_checked_call.h).
// So is each query's latency as the culler feels it: how many commands (draws and queries) had
// been submitted after it by the time its answer was known to be ready, when the culler polled
// it or waited for it (takeAnswerLatencies()).
// Conditional rendering (occsim/culling/contract/conditional_rendering.h) is
// glBeginConditionalRender on the query's GL_SAMPLES_PASSED object, GL_QUERY_WAIT or
// GL_QUERY_NO_WAIT; the driver decides. A query whose box reaches the near plane draws
// unconditionally (its samples mean nothing). Under deterministic latency the device decides
// readiness by its command count instead: NO_WAIT before the answer counts as ready draws
// unconditionally, after it the condition is evaluated with GL_QUERY_WAIT. For error measurement,
// an object drawn under a condition counts as drawn when the query passed samples
// (resolveConditionalDraws(), after the frame); so the query objects conditioned on stay unused
// until the next beginDrawnSet(). What the driver executed is counted apart from what was
// submitted: a GL_PRIMITIVES_GENERATED query around each block of conditional draws (not counted
// as a command) gives the triangles it executed, read after the frame (skippedConditionalDraws()).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/contract/render_device.h"
#include "render/gl_depth_pyramid.h"
#include "render/gl_gpu_driven_draws.h"
#include "render/gl_renderer.h"

namespace occsim {

class GlQueryDevice final : public RenderDevice, private ConditionalRendering {
  public:
    GlQueryDevice(GlRenderer& renderer, LatencyMode latency);
    ~GlQueryDevice() override;
    GlQueryDevice(const GlQueryDevice&) = delete;
    GlQueryDevice& operator=(const GlQueryDevice&) = delete;

    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override;
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override;
    bool isQueryReady(QueryId id) override;
    QueryAnswer takeAnswer(QueryId id) override;
    ConditionalRendering* conditionalRendering() override { return this; }
    // The depth pyramid (render/gl_depth_pyramid.h), made on first use; nullptr when this
    // context cannot compile its compute shaders.
    DepthPyramid* depthPyramid() override;
    // GPU-driven draws (render/gl_gpu_driven_draws.h), made on first use; nullptr when this
    // context cannot compile their shaders.
    GpuDrivenDraws* gpuDrivenDraws() override;
    // After the frame, outside any timing: adds the objects the GPU-driven draws drew this frame
    // to the drawn set and to the counters (objects_drawn, triangles_drawn), reading the units'
    // states back. Does nothing in a frame without them.
    void resolveGpuDrivenDraws();
    // The phase times of the frame the last resolveGpuDrivenDraws() resolved; nullptr when that
    // frame had no GPU-driven draws.
    const GlGpuDrivenDraws::PhaseTimes* gpuDrivenPhaseTimes() const {
        return gpu_frame_resolved_ ? &gpu_draws_->phaseTimes() : nullptr;
    }
    // The objects the GPU-driven draws drew in the frame the last resolveGpuDrivenDraws()
    // resolved (phase 1's, then phase 2's), for a trace of that frame.
    std::span<const uint32_t> gpuDrivenDrawnObjects() const { return gpu_drawn_objects_; }

    uint32_t queriesInFlight() const;

    // Which objects were drawn since the last beginDrawnSet(objects): what the culler actually put
    // on screen, so that error can say which visible objects it left out (an object drawn but
    // beaten at every pixel by a tie in depth is drawn, not missed). One store per draw.
    void beginDrawnSet(uint32_t objects);
    bool drew(uint32_t object) const {
        return object < drawn_mark_.size() && drawn_mark_[object] == drawn_set_;
    }
    // Objects the device leaves out of every draw, plain or conditional, from now on: those whose
    // entry in `may_draw` is 0 (one per object; empty: none left out). A draw left out is not a
    // command, not counted and not in the drawn set: what receiver-masked culling of a light's
    // view needs (a caster that shadows no visible receiver is not drawn, whatever the culler
    // decides). The span must stay valid while it is set.
    void setDrawFilter(std::span<const uint8_t> may_draw) { may_draw_ = may_draw; }
    // Query boxes (culling frame) for which `may_matter` is false are not drawn into their
    // query: they count no sample, so a node whose box may shadow no visible receiver is answered
    // hidden and culled with its subtree, as the paper tests nodes against its mask. The query
    // itself is still issued (answers keep their order and latency). Empty: every box is drawn.
    void setQueryFilter(std::function<bool(const Aabb&)> may_matter) {
        may_matter_ = std::move(may_matter);
    }
    // Query boxes the filter has left out, since the device was made.
    uint64_t filteredQueryBoxes() const { return filtered_query_boxes_; }
    // Marks in `submitted` (resized to the set's objects) every object the current set submitted
    // a draw of, conditional draws included whatever their query says (no read-back): during the
    // frame, a superset of what it drew.
    void markSubmitted(std::vector<uint8_t>& submitted) const;
    // Adds to the drawn set the objects drawn under a condition whose query passed samples (reads
    // those queries' results: call after the frame, outside any timing).
    void resolveConditionalDraws();
    // The draws of the current set that the driver skipped under their condition, and their
    // triangles: what was submitted (counters()) less what executed. Read from each conditional
    // block's GL_PRIMITIVES_GENERATED query (call after the frame, outside any timing). A block's
    // draws execute in order and, once its condition is known to be hidden, the rest are skipped
    // (GL_QUERY_NO_WAIT may execute the first ones unconditionally), so the executed ones are its
    // first draws up to the triangles the query counted.
    struct SkippedDraws {
        uint64_t objects = 0, triangles = 0;
    };
    SkippedDraws skippedConditionalDraws();
    // The latencies of the answers that became ready since the last call (in the order they did),
    // moved into `out` (cleared first; its capacity is reused).
    void takeAnswerLatencies(std::vector<uint32_t>& out);

  private:
    void drawIf(QueryId id, std::span<const uint32_t> objects, ConditionWait wait) override;
    void release(QueryId id) override;
    void retire(QueryId id);  // frees the id, or holds it until beginDrawnSet() if conditioned on
    void noteAnswered(QueryId id);
    bool pollReady(QueryId id);                       // asks the driver (or the latency model) once
    bool isLive(QueryId id, const char* call) const;  // issued and not yet taken
    bool leftOut(uint32_t object) const {
        return object < may_draw_.size() && may_draw_[object] == 0;
    }

    GlRenderer& renderer_;
    LatencyMode latency_;
    uint64_t commands_ = 0;             // draws and queries submitted so far
    std::vector<uint32_t> gl_queries_;  // QueryId -> GL query object
    std::vector<uint64_t> issued_at_;   // QueryId -> commands_ when issued
    // QueryId -> known to be ready (its latency is recorded): the cache that keeps an answer
    // from being polled again.
    std::vector<uint8_t> answered_;
    std::vector<uint8_t> live_;  // QueryId -> issued, answer not yet taken
    // QueryId -> a box of it reaches the near plane as drawn (nearPlaneTouchesBox): the samples
    // cannot be trusted, so the answer is "visible" whatever they say. Cullers never issue such
    // a query (they draw instead); this is the device's own guard for any that does.
    std::vector<uint8_t> near_eye_;
    std::vector<uint32_t> latencies_;  // since the last takeAnswerLatencies()
    std::vector<QueryId> free_ids_;
    std::vector<uint32_t> drawn_mark_;   // object -> drawn_set_ when drawn in the current set
    std::span<const uint8_t> may_draw_;  // setDrawFilter()
    std::function<bool(const Aabb&)> may_matter_;  // setQueryFilter()
    uint64_t filtered_query_boxes_ = 0;
    // Conditional draws of the current set: the object and the query it was conditioned on.
    struct ConditionalDraw {
        uint32_t object;
        QueryId query;
    };
    std::vector<ConditionalDraw> conditional_draws_;
    // The current set's conditional blocks (one drawIf each): its draws in conditional_draws_
    // and its GL_PRIMITIVES_GENERATED query in primitive_queries_.
    struct ConditionalBlock {
        uint32_t first_draw, draws, primitive_query;
    };
    std::vector<ConditionalBlock> blocks_;
    std::vector<uint32_t> primitive_queries_;  // a pool, used from 0 again each set
    std::vector<uint8_t>
        conditioned_;                // QueryId -> draws of the current set were conditioned on it
    std::vector<QueryId> held_ids_;  // released, kept until beginDrawnSet() for resolving
    uint32_t drawn_set_ = 1;
    std::unique_ptr<GlDepthPyramid> pyramid_;
    bool pyramid_tried_ = false;
    std::unique_ptr<GlGpuDrivenDraws> gpu_draws_;
    bool gpu_draws_tried_ = false;
    std::vector<GlRenderer::DrawCommand> gpu_drawn_;  // reused by resolveGpuDrivenDraws()
    bool gpu_frame_resolved_ = false;
    std::vector<uint32_t> gpu_drawn_objects_;
};

}  // namespace occsim
