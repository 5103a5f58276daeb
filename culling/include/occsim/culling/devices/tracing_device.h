// A RenderDevice decorator that records what a culler did in one frame, for pictures of its
// decisions (sim/output/birds_eye.h). It forwards every call to the wrapped device unchanged.
//
// Contract
// - While tracing (between beginTrace() and endTrace()), every drawObject() call is recorded in
//   order, and every issueQuery() call with its boxes. When takeAnswer() fetches the answer to a
//   query issued during the trace, the answer is recorded; a query whose answer is never
//   fetched before endTrace() stays "pending" (fetched == false).
// - Results fetched during the trace for queries issued before it (ids living across frames) are
//   only counted: their boxes are unknown to this device.
// - Conditional draws (conditional_rendering.h; offered when the wrapped device offers them) are
//   recorded among drawn_objects, as submitted, and in conditional_objects; the query they were
//   conditioned on is marked `conditional`. Its answer is never read back, so it stays unfetched.
// - GPU-driven draws (gpu_driven_draws.h) are the wrapped device's, forwarded: their draws are
//   decided on the device, so the host adds them to the trace once it has read them back after
//   the frame (addDeviceDecidedDraws()).
// - When not tracing, calls are forwarded and nothing is recorded.
// - Counters (draws, queries, wait time) are the wrapped device's: counters() forwards to it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/contract/render_device.h"

namespace occsim {

struct TracedQuery {
    std::vector<Aabb> boxes;         // one for a plain query, several for a multiquery
    std::vector<QueryTag> subjects;  // what the query decides, as the culler tagged it
    bool fetched = false;            // false: pending at the end of the trace
    bool visible = false;            // the answer, when fetched
    uint64_t samples = 0;            // the samples it rests on, when fetched
    bool conditional = false;        // draws were conditioned on it (the device decided them)
};

struct FrameTrace {
    uint64_t frame = 0;
    std::vector<uint32_t> drawn_objects;        // in draw order (conditional draws as submitted)
    std::vector<uint32_t> conditional_objects;  // those drawn under a query's condition
    std::vector<TracedQuery> queries;           // in issue order
    uint32_t earlier_results_fetched = 0;       // results of queries issued before the trace began

    uint32_t pendingQueries() const;
};

class TracingDevice final : public RenderDevice, private ConditionalRendering {
  public:
    explicit TracingDevice(RenderDevice& inner) : inner_(inner) {}

    // Starts recording a fresh trace for `frame` (any previous one is discarded).
    void beginTrace(uint64_t frame);
    void endTrace() { tracing_ = false; }
    // After endTrace(): objects the device drew on its own decisions during the traced frame
    // (GPU-driven draws), appended to its drawn objects.
    void addDeviceDecidedDraws(std::span<const uint32_t> objects) {
        trace_.drawn_objects.insert(trace_.drawn_objects.end(), objects.begin(), objects.end());
    }
    bool tracing() const { return tracing_; }
    const FrameTrace& trace() const { return trace_; }

    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override;
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override;
    bool isQueryReady(QueryId id) override { return inner_.isQueryReady(id); }
    QueryAnswer takeAnswer(QueryId id) override;

    ConditionalRendering* conditionalRendering() override {
        return inner_.conditionalRendering() ? this : nullptr;
    }
    DepthPyramid* depthPyramid() override { return inner_.depthPyramid(); }
    GpuDrivenDraws* gpuDrivenDraws() override { return inner_.gpuDrivenDraws(); }
    const DeviceCounters& counters() const override { return inner_.counters(); }
    void resetCounters() override { inner_.resetCounters(); }

  private:
    static constexpr size_t kClosed = SIZE_MAX;

    void makeRoom(TracedQuery& q) const;
    void drawIf(QueryId id, std::span<const uint32_t> objects, ConditionWait wait) override;
    void release(QueryId id) override;

    RenderDevice& inner_;
    bool tracing_ = false;
    FrameTrace trace_;
    // Per query id, its index in trace_.queries until its result is fetched, else kClosed. Ids are
    // small and reused by the wrapped device, so a flat array indexed by id serves as the map.
    std::vector<size_t> open_;
    // The traced queries of earlier traces, kept with their box and tag lists' storage, so that
    // tracing every frame (the viewer's trace mode) allocates nothing once frames are alike.
    std::vector<TracedQuery> spare_;
    size_t room_boxes_ = 0;  // what every stored query has room for (see issueQuery())
    size_t room_subjects_ = 0;
};

}  // namespace occsim
