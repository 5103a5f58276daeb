#include "culling/scripted_query_device.h"

#include <algorithm>
#include <cassert>
#include <utility>

namespace occsim {

void ScriptedQueryDevice::setVisibility(std::vector<uint8_t> visible, std::vector<Aabb> object_boxes) {
    assert(visible.size() == object_boxes.size());
    visible_ = std::move(visible);
    boxes_ = std::move(object_boxes);
}

void ScriptedQueryDevice::updateVisibility(std::span<const uint8_t> visible,
                                           std::span<const Aabb> object_boxes) {
    assert(visible.size() == object_boxes.size());
    visible_.assign(visible.begin(), visible.end());
    boxes_.assign(object_boxes.begin(), object_boxes.end());
}

void ScriptedQueryDevice::drawObject(uint32_t object) {
    drawn_.push_back(object);
    ++commands_;
    ++counters_.objects_drawn;
}

QueryId ScriptedQueryDevice::issueQuery(std::span<const Aabb> boxes,
                                        std::span<const QueryTag> subjects) {
    uint64_t samples = 0;
    for (size_t o = 0; o < boxes_.size(); ++o) {
        if (!visible_[o]) continue;
        for (const Aabb& q : boxes) {
            if (overlaps(q, boxes_[o])) {
                ++samples;
                break;
            }
        }
    }
    queried_.insert(queried_.end(), boxes.begin(), boxes.end());
    tags_.push_back(subjects.empty() ? QueryTag{} : subjects.front());
    QueryId id = 0;
    while (id < queries_.size() && queries_[id].in_use) ++id;
    if (id == queries_.size()) queries_.push_back({});
    queries_[id] = {commands_++, samples, true};
    ++counters_.queries_issued;
    counters_.query_boxes += boxes.size();
    max_pending_ = std::max(max_pending_, pendingQueries());
    return id;
}

bool ScriptedQueryDevice::isQueryReady(QueryId id) {
    assert(id < queries_.size() && queries_[id].in_use);
    return commands_ - queries_[id].issued_at > latency_;
}

uint64_t ScriptedQueryDevice::queryResult(QueryId id) {
    if (!isQueryReady(id)) ++counters_.results_waited;
    ++counters_.results_fetched;
    queries_[id].in_use = false;
    return queries_[id].result;
}

void ScriptedQueryDevice::clearLog() {
    drawn_.clear();
    queried_.clear();
    tags_.clear();
}

uint32_t ScriptedQueryDevice::pendingQueries() const {
    uint32_t n = 0;
    for (const Pending& p : queries_) n += p.in_use ? 1 : 0;
    return n;
}

}  // namespace occsim
