#include "culling/approximate_device.h"

#include <cstring>

namespace occsim {

ApproximateDevice::ApproximateDevice(RenderDevice& inner, ApproximationOptions options)
    : inner_(inner), options_(options) {}

uint64_t ApproximateDevice::keyOf(std::span<const Aabb> boxes) const {
    // FNV-1a over the boxes' bytes: a node queried with the same bounds as last time finds its
    // last result; bounds that moved are a new key (and the device waits, as it should).
    uint64_t h = 1469598103934665603ull;
    for (const Aabb& b : boxes) {
        unsigned char bytes[sizeof(Aabb)];
        std::memcpy(bytes, &b, sizeof bytes);
        for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    }
    return h;
}

uint64_t ApproximateDevice::apply(uint64_t samples) const {
    return samples <= options_.threshold_pixels ? 0 : samples;
}

void ApproximateDevice::collectLateResults() {
    // Results arrive in issue order: stop at the first that is not ready.
    while (!late_.empty() && inner_.isQueryReady(late_.front())) {
        const QueryId id = late_.front();
        late_.pop_front();
        last_[key_of_id_[id]] = inner_.queryResult(id);
    }
}

void ApproximateDevice::drawObject(uint32_t object) { inner_.drawObject(object); }

QueryId ApproximateDevice::issueQuery(std::span<const Aabb> boxes,
                                      std::span<const QueryTag> subjects) {
    if (options_.stale_results) collectLateResults();
    const QueryId id = inner_.issueQuery(boxes, subjects);
    if (id >= key_of_id_.size()) key_of_id_.resize(id + 1);
    key_of_id_[id] = keyOf(boxes);
    return id;
}

bool ApproximateDevice::isQueryReady(QueryId id) {
    // A stale answer is always available at once when there is one to give.
    if (options_.stale_results && !inner_.isQueryReady(id)) return last_.count(key_of_id_[id]) > 0;
    return inner_.isQueryReady(id);
}

uint64_t ApproximateDevice::queryResult(QueryId id) {
    if (options_.stale_results && !inner_.isQueryReady(id)) {
        const auto it = last_.find(key_of_id_[id]);
        if (it != last_.end()) {
            ++stale_answers_;
            late_.push_back(id);
            return apply(it->second);
        }
    }
    const uint64_t samples = inner_.queryResult(id);
    last_[key_of_id_[id]] = samples;
    return apply(samples);
}

}  // namespace occsim
