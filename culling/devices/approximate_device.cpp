#include "occsim/culling/devices/approximate_device.h"

#include <algorithm>
#include <cstring>

#include "occsim/culling/contract/query_id_check.h"

namespace occsim {

ApproximateDevice::ApproximateDevice(RenderDevice& inner, ApproximationOptions options)
    : inner_(inner), options_(options) {
    if (options_.stale_results) last_.resize(kLastResultSlots);
}

uint64_t ApproximateDevice::keyOf(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) {
    // FNV-1a over the subjects (a node queried again finds its last result even when its bounds
    // moved), or over the boxes' bytes for an untagged query. Never 0: 0 marks an empty slot.
    uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* data, size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    };
    bool tagged = false;
    for (const QueryTag& tag : subjects) {
        if (tag.index == QueryTag::kUntagged) continue;
        tagged = true;
        const uint8_t subject = static_cast<uint8_t>(tag.subject);
        mix(&subject, sizeof subject);
        mix(&tag.index, sizeof tag.index);
    }
    if (!tagged) {
        for (const Aabb& b : boxes) {
            unsigned char bytes[sizeof(Aabb)];
            std::memcpy(bytes, &b, sizeof bytes);
            mix(bytes, sizeof bytes);
        }
    }
    return h == 0 ? 1 : h;
}

const ApproximateDevice::LastResult* ApproximateDevice::findLast(uint64_t key) const {
    // Linear probing over a few slots; a table this size holds far more subjects than a frame
    // queries, so a miss only means waiting once.
    for (size_t i = 0; i < 4; ++i) {
        const LastResult& slot = last_[(key + i) & (kLastResultSlots - 1)];
        if (slot.key == key) return &slot;
        if (slot.key == 0) return nullptr;
    }
    return nullptr;
}

void ApproximateDevice::storeLast(uint64_t key, uint64_t samples) {
    if (!options_.stale_results) return;
    for (size_t i = 0; i < 4; ++i) {
        LastResult& slot = last_[(key + i) & (kLastResultSlots - 1)];
        if (slot.key == key || slot.key == 0) {
            slot = {key, samples};
            return;
        }
    }
    last_[key & (kLastResultSlots - 1)] = {key, samples};  // evict the first probe
}

QueryAnswer ApproximateDevice::answerFrom(uint64_t samples, bool waited) const {
    return {samples > options_.threshold_pixels, samples, waited};
}

void ApproximateDevice::collectLateResults() {
    // Results arrive in issue order: stop at the first that is not ready.
    size_t done = 0;
    while (done < late_.size() && inner_.isQueryReady(late_[done])) {
        const QueryId id = late_[done++];
        storeLast(key_of_id_[id], inner_.takeAnswer(id).samples);
    }
    late_.erase(late_.begin(), late_.begin() + static_cast<std::ptrdiff_t>(done));
}

void ApproximateDevice::drawObject(uint32_t object) { inner_.drawObject(object); }

QueryId ApproximateDevice::issueQuery(std::span<const Aabb> boxes,
                                      std::span<const QueryTag> subjects) {
    if (options_.stale_results) collectLateResults();
    const QueryId id = inner_.issueQuery(boxes, subjects);
    if (id >= key_of_id_.size()) key_of_id_.resize(id + 1);
    key_of_id_[id] = keyOf(boxes, subjects);
    if (options_.stale_results) open_.push_back(id);
    return id;
}

bool ApproximateDevice::answerable(QueryId id) {
    return inner_.isQueryReady(id) || findLast(key_of_id_[id]) != nullptr;
}

bool ApproximateDevice::isQueryReady(QueryId id) {
    if (kCheckQueryIds && id >= key_of_id_.size()) {
        failQueryId("ApproximateDevice", "isQueryReady", id, "was never issued");
    }
    if (inner_.isQueryReady(id)) return true;
    if (!options_.stale_results) return false;
    // A stale answer may be given at once, but only when every earlier open query could be
    // answered too: results must still become ready in issue order.
    for (QueryId earlier : open_) {
        if (!answerable(earlier)) return false;
        if (earlier == id) return true;
    }
    return false;
}

QueryAnswer ApproximateDevice::takeAnswer(QueryId id) {
    if (kCheckQueryIds && id >= key_of_id_.size()) {
        failQueryId("ApproximateDevice", "takeAnswer", id, "was never issued");
    }
    if (options_.stale_results) {
        const auto at = std::find(open_.begin(), open_.end(), id);
        if (at != open_.end()) open_.erase(at);
        if (!inner_.isQueryReady(id)) {
            if (const LastResult* last = findLast(key_of_id_[id])) {
                ++stale_answers_;
                late_.push_back(id);
                return answerFrom(last->samples, false);
            }
        }
    }
    const QueryAnswer inner = inner_.takeAnswer(id);
    storeLast(key_of_id_[id], inner.samples);
    return answerFrom(inner.samples, inner.waited);
}

}  // namespace occsim
