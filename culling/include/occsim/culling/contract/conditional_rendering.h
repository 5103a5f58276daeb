// Conditional rendering, an optional capability of a RenderDevice (DeviceFeature
// kConditionalRendering; RenderDevice::conditionalRendering() is nullptr on a device without it).
// It is OpenGL's glBeginConditionalRender (3.0): draws that the device executes only if an
// occlusion query issued earlier passed samples. The culler never reads the answer: the device
// (on a GPU, the GPU itself) decides, so the culler never waits.
//
// Contract
// - drawIf(id, objects, wait): submits one draw per object, executed only if query `id` (issued
//   by this device with issueQuery() and not yet released or taken) is visible. Each submitted
//   draw counts in the device's counters as a draw (objects_drawn, triangles_drawn) and as a
//   conditional draw (conditional_draws): counters say what was submitted, not what the device
//   executed, which nobody learns without reading the answer back.
// - `wait` says what the device does when the answer is not known yet at the draw:
//   ConditionWait::Wait waits for it (on a GPU the GPU waits, not the CPU; GL_QUERY_WAIT),
//   ConditionWait::NoWait executes the draws unconditionally (GL_QUERY_NO_WAIT). So NoWait can
//   only draw more than Wait, never less: both are conservative.
// - "Visible" is the device's plain rule: any sample passed (a decorator's pixel threshold or
//   stale answers cannot apply to an answer the device evaluates itself: ApproximateDevice offers
//   no conditional rendering while it approximates). A query whose box reaches the near plane as
//   drawn counts as visible, as its taken answer would (the GL device's own guard).
// - Under deterministic latency (LatencyMode), an answer is known only once the device's usual
//   number of later commands was submitted after the query, exactly as for takeAnswer(); NoWait
//   then draws unconditionally before that and evaluates the condition after it, so which draws
//   execute depends on the scenario alone.
// - release(id): ends the query's life without reading its answer; the id is released as
//   takeAnswer() would release it (a query used as a condition need not be taken). Several drawIf
//   calls may use one id before it is released. Using or releasing an id not in flight is a
//   programming error, checked like takeAnswer()'s (query_id_check.h).
#pragma once

#include <cstdint>
#include <span>

#include "occsim/culling/contract/render_device.h"

namespace occsim {

// What a conditional draw does when the query's answer is not known yet.
enum class ConditionWait : uint8_t {
    Wait,    // wait for the answer (GL_QUERY_WAIT)
    NoWait,  // draw unconditionally (GL_QUERY_NO_WAIT)
};

class ConditionalRendering {
  public:
    virtual ~ConditionalRendering() = default;

    virtual void drawIf(QueryId id, std::span<const uint32_t> objects, ConditionWait wait) = 0;
    virtual void release(QueryId id) = 0;

    void drawIf(QueryId id, uint32_t object, ConditionWait wait) {
        drawIf(id, std::span<const uint32_t>(&object, 1), wait);
    }
};

}  // namespace occsim
