// Two ways to trade image error for time (ApproximationOptions, approximation_options.h),
// applied to any culler by wrapping its RenderDevice:
//
// - A pixel threshold (approximate visibility, as in the CHC paper): a query that passes at most
//   `threshold_pixels` samples is answered occluded (QueryAnswer::visible false; its samples
//   are reported as they were). This device is the only place the threshold is applied.
// - Stale results: a result that is not ready when the culler asks for it is not waited for;
//   the last result seen for the same subjects (the nodes or objects the query was tagged with,
//   or its boxes when untagged; normally from the previous frame) is returned instead, and the
//   real result, once it arrives, becomes the "last result" for next time. Without a previous
//   result the device waits as usual. A stale answer never counts as waited for.
//
// Both make conservative cullers approximate; the error shows in the numbers. With threshold 0
// and stale results off this device changes nothing.
//
// Conditional rendering (conditional_rendering.h) is offered only while neither knob is active:
// the wrapped device evaluates a condition on the raw samples, where no threshold or stale answer
// can reach it, so forwarding it would silently ignore the knobs. A culler that needs it is then
// refused (requireDeviceFeatures); the built-in `conditional` does not issue queries in the
// registry's sense, so runs never put it behind this device.
//
// Contract: results still become ready in issue order (a query answerable from a stale result is
// ready only when every earlier open query is ready or answerable too), and the device allocates
// nothing per frame once its tables are sized: the last results live in a fixed-size table (a
// cache: a subject whose entry was overwritten is simply waited for).
#pragma once

#include <cstdint>
#include <vector>

#include "occsim/culling/contract/render_device.h"
#include "occsim/culling/devices/approximation_options.h"

namespace occsim {

class ApproximateDevice final : public RenderDevice {
  public:
    ApproximateDevice(RenderDevice& inner, ApproximationOptions options);

    using RenderDevice::issueQuery;
    void drawObject(uint32_t object) override;
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override;
    bool isQueryReady(QueryId id) override;
    QueryAnswer takeAnswer(QueryId id) override;

    // Results fetched late (after a stale answer was given) still pending in the wrapped device.
    size_t lateResultsPending() const { return late_.size(); }
    uint64_t staleAnswers() const { return stale_answers_; }

    // The wrapped device does the work, so its counters are the true ones.
    ConditionalRendering* conditionalRendering() override {
        return options_.active() ? nullptr : inner_.conditionalRendering();
    }
    DepthPyramid* depthPyramid() override { return inner_.depthPyramid(); }
    GpuDrivenDraws* gpuDrivenDraws() override { return inner_.gpuDrivenDraws(); }
    const DeviceCounters& counters() const override { return inner_.counters(); }
    void resetCounters() override { inner_.resetCounters(); }

  private:
    static constexpr size_t kLastResultSlots = size_t{1} << 16;

    struct LastResult {
        uint64_t key = 0;  // 0 = empty
        uint64_t samples = 0;
    };

    static uint64_t keyOf(std::span<const Aabb> boxes, std::span<const QueryTag> subjects);
    const LastResult* findLast(uint64_t key) const;
    void storeLast(uint64_t key, uint64_t samples);
    bool answerable(QueryId id);  // ready in the wrapped device, or a stale answer exists
    void collectLateResults();
    QueryAnswer answerFrom(uint64_t samples, bool waited) const;  // applies the threshold

    RenderDevice& inner_;
    ApproximationOptions options_;
    std::vector<uint64_t> key_of_id_;  // QueryId -> subjects key
    std::vector<LastResult> last_;     // open addressing over key, kLastResultSlots entries
    std::vector<QueryId> open_;        // issued, not fetched, in issue order (stale mode only)
    std::vector<QueryId> late_;        // answered stale, real result pending, in issue order
    uint64_t stale_answers_ = 0;
};

}  // namespace occsim
