#include "culling/tracing_device.h"

namespace occsim {

uint32_t FrameTrace::pendingQueries() const {
    uint32_t n = 0;
    for (const TracedQuery& q : queries) n += q.fetched ? 0 : 1;
    return n;
}

void TracingDevice::beginTrace(uint64_t frame) {
    trace_ = FrameTrace{};
    trace_.frame = frame;
    open_.clear();
    tracing_ = true;
}

void TracingDevice::drawObject(uint32_t object) {
    if (tracing_) trace_.drawn_objects.push_back(object);
    inner_.drawObject(object);
}

QueryId TracingDevice::issueQuery(std::span<const Aabb> boxes,
                                  std::span<const QueryTag> subjects) {
    const QueryId id = inner_.issueQuery(boxes, subjects);
    if (tracing_) {
        // The inner device may reuse an id once its result was fetched, so the map holds only
        // ids whose results are still open.
        open_[id] = trace_.queries.size();
        trace_.queries.push_back({std::vector<Aabb>(boxes.begin(), boxes.end()),
                                  std::vector<QueryTag>(subjects.begin(), subjects.end()), false,
                                  0});
    }
    return id;
}

uint64_t TracingDevice::queryResult(QueryId id) {
    const uint64_t samples = inner_.queryResult(id);
    if (!tracing_) return samples;
    const auto it = open_.find(id);
    if (it == open_.end()) {
        ++trace_.earlier_results_fetched;
        return samples;
    }
    TracedQuery& q = trace_.queries[it->second];
    q.fetched = true;
    q.samples = samples;
    open_.erase(it);
    return samples;
}

}  // namespace occsim
