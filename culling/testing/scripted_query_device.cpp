#include "occsim/culling/testing/scripted_query_device.h"

#include <algorithm>
#include <cassert>
#include <utility>

namespace occsim {

void ScriptedQueryDevice::setVisibility(std::vector<uint8_t> visible,
                                        std::vector<Aabb> object_boxes) {
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
    queries_.countDraw();
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
    const QueryId id = queries_.issue(samples, boxes.size(), counters_);
    max_pending_ = std::max(max_pending_, pendingQueries());
    return id;
}

void ScriptedQueryDevice::drawIf(QueryId id, std::span<const uint32_t> objects,
                                 ConditionWait wait) {
    const bool holds = queries_.conditionHolds(id, wait);  // decided when the draws are submitted
    for (uint32_t object : objects) {
        (holds ? drawn_ : skipped_).push_back(object);
        queries_.countDraw();
        ++counters_.objects_drawn;
        ++counters_.conditional_draws;
    }
}

bool ScriptedQueryDevice::isQueryReady(QueryId id) { return queries_.ready(id); }

QueryAnswer ScriptedQueryDevice::takeAnswer(QueryId id) { return queries_.take(id, counters_); }

void ScriptedQueryDevice::clearLog() {
    drawn_.clear();
    skipped_.clear();
    queried_.clear();
    tags_.clear();
}

}  // namespace occsim
