#include "occsim/culling/devices/tracing_device.h"

#include <algorithm>
#include <bit>
#include <utility>

namespace occsim {

uint32_t FrameTrace::pendingQueries() const {
    uint32_t n = 0;
    for (const TracedQuery& q : queries) n += q.fetched ? 0 : 1;
    return n;
}

void TracingDevice::beginTrace(uint64_t frame) {
    // The last trace's vectors are emptied, not freed: their storage serves this one. Pushed in
    // reverse, so that this frame's i-th query takes the storage of the last frame's i-th, which
    // usually had as many boxes.
    for (size_t i = trace_.queries.size(); i-- > 0;) spare_.push_back(std::move(trace_.queries[i]));
    trace_.queries.clear();
    trace_.drawn_objects.clear();
    trace_.conditional_objects.clear();
    trace_.frame = frame;
    trace_.earlier_results_fetched = 0;
    std::fill(open_.begin(), open_.end(), kClosed);
    tracing_ = true;
}

void TracingDevice::drawObject(uint32_t object) {
    if (tracing_) trace_.drawn_objects.push_back(object);
    inner_.drawObject(object);
}

void TracingDevice::makeRoom(TracedQuery& q) const {
    q.boxes.reserve(room_boxes_);
    q.subjects.reserve(room_subjects_);
}

QueryId TracingDevice::issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) {
    const QueryId id = inner_.issueQuery(boxes, subjects);
    if (tracing_) {
        // The inner device may reuse an id once its result was fetched, so the map holds only
        // ids whose results are still open.
        if (id >= open_.size()) open_.resize(id + 1, kClosed);
        open_[id] = trace_.queries.size();
        // Every stored query has room for the largest multiquery seen so far, grown in powers of
        // two, and the store of queries grows by doubling as a vector's storage does: so a frame
        // allocates only when it issues more queries, or a larger multiquery, than any before it
        // (CHC++ spreads its queries at random, so the count varies from frame to frame).
        if (boxes.size() > room_boxes_ || subjects.size() > room_subjects_) {
            room_boxes_ = std::bit_ceil(std::max(room_boxes_, boxes.size()));
            room_subjects_ = std::bit_ceil(std::max(room_subjects_, subjects.size()));
            for (TracedQuery& q : trace_.queries) makeRoom(q);
            for (TracedQuery& q : spare_) makeRoom(q);
        }
        if (spare_.empty()) {
            spare_.resize(std::max<size_t>(trace_.queries.size(), 16));
            for (TracedQuery& q : spare_) makeRoom(q);
        }
        trace_.queries.push_back(std::move(spare_.back()));
        spare_.pop_back();
        TracedQuery& q = trace_.queries.back();
        q.boxes.assign(boxes.begin(), boxes.end());
        q.subjects.assign(subjects.begin(), subjects.end());
        q.fetched = false;
        q.visible = false;
        q.samples = 0;
        q.conditional = false;
    }
    return id;
}

void TracingDevice::drawIf(QueryId id, std::span<const uint32_t> objects, ConditionWait wait) {
    if (tracing_) {
        trace_.drawn_objects.insert(trace_.drawn_objects.end(), objects.begin(), objects.end());
        trace_.conditional_objects.insert(trace_.conditional_objects.end(), objects.begin(),
                                          objects.end());
        if (id < open_.size() && open_[id] != kClosed) trace_.queries[open_[id]].conditional = true;
    }
    inner_.conditionalRendering()->drawIf(id, objects, wait);
}

void TracingDevice::release(QueryId id) {
    inner_.conditionalRendering()->release(id);
    if (tracing_ && id < open_.size()) open_[id] = kClosed;  // the id may be reused: unfetched
}

QueryAnswer TracingDevice::takeAnswer(QueryId id) {
    const QueryAnswer answer = inner_.takeAnswer(id);
    if (!tracing_) return answer;
    if (id >= open_.size() || open_[id] == kClosed) {
        ++trace_.earlier_results_fetched;
        return answer;
    }
    TracedQuery& q = trace_.queries[open_[id]];
    q.fetched = true;
    q.visible = answer.visible;
    q.samples = answer.samples;
    open_[id] = kClosed;
    return answer;
}

}  // namespace occsim
