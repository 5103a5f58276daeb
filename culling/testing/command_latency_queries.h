// The query bookkeeping of the CPU test devices (ScriptedQueryDevice, DepthRasterDevice): an
// answer, known when the query is issued, counts as ready only after `latency` later commands
// (draws or queries), like --deterministic-latency on the GL device. Query slots are reused, so a
// steady state allocates nothing; `counters` are the owning device's.
#pragma once

#include "occsim/culling/contract/render_device.h"

#include <cassert>
#include <cstdint>
#include <vector>

namespace occsim {

class CommandLatencyQueries {
public:
    explicit CommandLatencyQueries(uint32_t latency_commands) : latency_(latency_commands) {}

    void countDraw() { ++commands_; }

    QueryId issue(uint64_t samples, size_t boxes, DeviceCounters& counters) {
        QueryId id = 0;
        while (id < slots_.size() && slots_[id].in_use) ++id;
        if (id == slots_.size()) slots_.push_back({});
        slots_[id] = {commands_++, samples, true};
        ++counters.queries_issued;
        counters.query_boxes += boxes;
        return id;
    }

    bool ready(QueryId id) const {
        assert(id < slots_.size() && slots_[id].in_use);
        return commands_ - slots_[id].issued_at > latency_;
    }

    uint64_t take(QueryId id, DeviceCounters& counters) {
        if (!ready(id)) ++counters.results_waited;
        ++counters.results_fetched;
        slots_[id].in_use = false;
        return slots_[id].result;
    }

    uint32_t pending() const {
        uint32_t n = 0;
        for (const Slot& s : slots_) n += s.in_use ? 1 : 0;
        return n;
    }

private:
    struct Slot {
        uint64_t issued_at;
        uint64_t result;
        bool in_use;
    };
    uint32_t latency_;
    uint64_t commands_ = 0;
    std::vector<Slot> slots_;
};

}  // namespace occsim
