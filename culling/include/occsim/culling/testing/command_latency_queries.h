// The query bookkeeping of the CPU test devices (ScriptedQueryDevice, DepthRasterDevice): an
// answer, known when the query is issued, counts as ready only after `latency` later commands
// (draws or queries), like --deterministic-latency on the GL device. Query slots are reused, so a
// steady state allocates nothing; `counters` are the owning device's. Every id handed back is
// checked in every build (query_id_check.h): taking an answer twice, or asking about an id never
// issued, aborts with a message naming `device`.
#pragma once

#include <cstdint>
#include <vector>

#include "occsim/culling/contract/conditional_rendering.h"
#include "occsim/culling/contract/query_id_check.h"
#include "occsim/culling/contract/render_device.h"

namespace occsim {

class CommandLatencyQueries {
  public:
    CommandLatencyQueries(uint32_t latency_commands, const char* device)
        : latency_(latency_commands), device_(device) {}

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
        checkLive(id, "isQueryReady");
        return isReady(id);
    }

    QueryAnswer take(QueryId id, DeviceCounters& counters) {
        checkLive(id, "takeAnswer");
        const bool waited = !isReady(id);
        if (waited) ++counters.results_waited;
        ++counters.results_fetched;
        slots_[id].in_use = false;
        return {slots_[id].result > 0, slots_[id].result, waited};
    }

    // Whether draws under query `id`'s condition execute, decided as a GPU would when they are
    // submitted now (conditional_rendering.h): Wait, or an answer already ready, executes them iff
    // the answer is visible; NoWait before the answer is ready executes them unconditionally.
    bool conditionHolds(QueryId id, ConditionWait wait) const {
        checkLive(id, "drawIf");
        if (wait == ConditionWait::NoWait && !isReady(id)) return true;
        return slots_[id].result > 0;
    }

    // Ends a query without taking its answer (ConditionalRendering::release).
    void release(QueryId id) {
        checkLive(id, "release");
        slots_[id].in_use = false;
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

    bool isReady(QueryId id) const { return commands_ - slots_[id].issued_at > latency_; }
    void checkLive(QueryId id, const char* call) const {
        if (id >= slots_.size()) failQueryId(device_, call, id, "was never issued");
        if (!slots_[id].in_use) failQueryId(device_, call, id, "is not in flight (already taken)");
    }

    uint32_t latency_;
    const char* device_;
    uint64_t commands_ = 0;
    std::vector<Slot> slots_;
};

}  // namespace occsim
