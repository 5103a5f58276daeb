// A RenderDevice decorator that records what a culler did in one frame, for pictures of its
// decisions (sim/birds_eye.h). It forwards every call to the wrapped device unchanged.
//
// Contract
// - While tracing (between beginTrace() and endTrace()), every drawObject() call is recorded in
//   order, and every issueQuery() call with its boxes. When queryResult() fetches the result of a
//   query issued during the trace, its sample count is recorded; a query whose result is never
//   fetched before endTrace() stays "pending" (fetched == false).
// - Results fetched during the trace for queries issued before it (ids living across frames) are
//   only counted: their boxes are unknown to this device.
// - When not tracing, calls are forwarded and nothing is recorded.
// - Counters (draws, queries, wait time) are the wrapped device's: counters() forwards to it.
#pragma once

#include "culling/render_device.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace occsim {

struct TracedQuery {
    std::vector<Aabb> boxes;         // one for a plain query, several for a multiquery
    std::vector<QueryTag> subjects;  // what the query decides, as the culler tagged it
    bool fetched = false;     // false: pending at the end of the trace
    uint64_t samples = 0;     // the result, when fetched
};

struct FrameTrace {
    uint64_t frame = 0;
    std::vector<uint32_t> drawn_objects;  // in draw order
    std::vector<TracedQuery> queries;     // in issue order
    uint32_t earlier_results_fetched = 0; // results of queries issued before the trace began

    uint32_t pendingQueries() const;
};

class TracingDevice final : public RenderDevice {
public:
    explicit TracingDevice(RenderDevice& inner) : inner_(inner) {}

    // Starts recording a fresh trace for `frame` (any previous one is discarded).
    void beginTrace(uint64_t frame);
    void endTrace() { tracing_ = false; }
    bool tracing() const { return tracing_; }
    const FrameTrace& trace() const { return trace_; }

    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override;
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override;
    bool isQueryReady(QueryId id) override { return inner_.isQueryReady(id); }
    uint64_t queryResult(QueryId id) override;

    const DeviceCounters& counters() const override { return inner_.counters(); }
    void resetCounters() override { inner_.resetCounters(); }

private:
    RenderDevice& inner_;
    bool tracing_ = false;
    FrameTrace trace_;
    std::unordered_map<QueryId, size_t> open_;  // id -> index in trace_.queries, until fetched
};

}  // namespace occsim
