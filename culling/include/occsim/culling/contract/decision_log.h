// Why a culler drew or left out each object of a frame, as the culler saw it: an optional sink a
// host hands over in CullFrame::decisions (null when nobody records, so a culler pays one branch
// per decision), and the plain-data records a culler appends to it. docs/objects.md lists the
// kinds and how `occsim why` words them.
//
// Contract
// - A record names its subject as a query does (QueryTag): a node's whole subtree, the objects
//   stored in a node itself, or one object. A culler records a decision when it makes it, so a
//   frame's records are in decision order; the host resolves them per object after the frame
//   (occsim/culling/tree/decision_resolution.h): the last record that covers an object is its
//   reason, except that a record on a node never overrides an object's own FrustumCulled (a box
//   outside the frustum stays outside for the whole frame).
// - A record says why, not what happened: whether an object was drawn is the device's to say
//   (a conditional draw executes or not on the device's answer), and the host keeps the two apart.
// - Fields that do not apply to a kind keep their defaults (kNoFrame, kNoLevel, 0).
// - The log allocates nothing once it is large enough: clear() keeps its capacity.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "occsim/culling/contract/render_device.h"

namespace occsim {

// The reason kinds. The numbers are stored in objects.sqlite: append, never renumber.
enum class DecisionKind : uint8_t {
    NoReasonGiven = 0,        // the culler recorded none (a plugin that gives no reasons)
    FrustumCulled = 1,        // its box (or its node's) is outside the view frustum
    CulledOnQuery = 2,        // a query answered occluded: query_frame, samples
    DrawnOnQuery = 3,         // a query answered visible: query_frame, samples
    DrawnOnStatistics = 4,    // statistical: no query, the decay curve's interval has not run out
    DrawnOnCostModel = 5,     // statistical+: the cost model put the query off
    DrawnNearPlane = 6,       // the near plane may cut its box: drawn, never tested
    DrawnNoTest = 7,          // drawn with no test (vfc, a fallback frame, never tested yet)
    DrawnQueryInFlight = 8,   // drawn on its last answer while a new query (query_frame) runs
    DrawnAssumedVisible = 9,  // found visible at query_frame, assumed visible until a later frame
    CulledOnPyramid = 10,     // hzb: hidden by the depth pyramid (phase 2, level)
    DrawnOnPyramid = 11,      // hzb: phase 1 (visible last frame) or phase 2 (passed at level)
    CulledOnTiles = 12,       // masked: its box failed the software depth buffer's tile test
    DrawnOnTiles = 13,        // masked: its box passed the tile test
    DrawnConditional = 14,    // conditional: submitted under its query's condition; device decides
    DrawnByOracle = 15,       // ideal: ground truth saw it
    CulledByOracle = 16,      // ideal: ground truth did not see it
    CulledOnBoxRaster = 17,   // raster: no fragment of its box passed the depth test (phase 2)
    DrawnOnBoxRaster = 18,    // raster: phase 1 (visible last frame) or its box passed (phase 2)
};
inline constexpr uint32_t kDecisionKinds = 19;

// Refinements of a kind, as bits.
enum DecisionFlag : uint8_t {
    kDecisionWaited = 1u << 0,      // the culler blocked for the answer
    kDecisionMultiquery = 1u << 1,  // the answer was a multiquery's over several nodes (CHC++)
    kDecisionDistance = 1u << 2,    // statistical: the interval is in metres travelled, not seconds
    kDecisionFallback = 1u << 3,    // statistical+: a fallback frame of frustum culling only
    kDecisionOccluder = 1u << 4,    // masked: rasterised into the buffer as an occluder this frame
    kDecisionNoPyramid = 1u << 5,   // hzb: phase 1 drew nothing, so the pyramid hid nothing
    kDecisionNodeUnit = 1u << 6,    // hzb, masked: decided for its node, not for itself
};

struct Decision {
    static constexpr uint32_t kNoFrame = UINT32_MAX;
    static constexpr uint8_t kNoLevel = UINT8_MAX;

    DecisionKind kind = DecisionKind::NoReasonGiven;
    uint8_t phase = 0;         // hzb: 1 or 2
    uint8_t level = kNoLevel;  // hzb: the pyramid level its footprint was read at
    uint8_t flags = 0;         // DecisionFlag bits
    // The frame the deciding query was issued in (answers, queries in flight), or of the last
    // query that found it visible (statistics, assumed visible).
    uint32_t query_frame = kNoFrame;
    uint32_t samples = 0;  // the answer's samples, saturated
    // Statistics: the interval the decay curve gave (seconds, or metres with kDecisionDistance),
    // the time (or travel) after which it is queried again, and the visible answers in its
    // history (`count`) out of `history` answers.
    float interval = 0.0f;
    float next_query = 0.0f;
    uint8_t count = 0;
    uint8_t history = 0;
    uint16_t reserved = 0;
    // The frame it is tested again in (assumed visible, async's re-test); kNoFrame when unknown.
    uint32_t next_query_frame = kNoFrame;
};

struct DecisionRecord {
    QueryTag subject;  // a node's subtree, a node's own objects, or one object
    Decision decision;
};
static_assert(sizeof(DecisionRecord) == 36, "a record is a handful of words: keep it plain");

class DecisionLog {
  public:
    void clear() { records_.clear(); }
    void reserve(size_t records) { records_.reserve(records); }
    void add(QueryTag subject, const Decision& decision) {
        records_.push_back({subject, decision});
    }
    std::span<const DecisionRecord> records() const { return records_; }

  private:
    std::vector<DecisionRecord> records_;
};

// Appends the record when there is a log: the one branch a culler pays per decision when nobody
// records.
inline void recordDecision(DecisionLog* log, QueryTag subject, const Decision& decision) {
    if (log) log->add(subject, decision);
}

// The kind's name as stored and printed ("culled on query"), and whether it means drawn: 1 drawn,
// 0 not drawn, -1 the device decides or nobody said (conditional, no reason given).
std::string_view decisionKindName(DecisionKind kind);
int decisionKindDraws(DecisionKind kind);

// Shorthands for a culler's records: the one place a culler builds a Decision.
inline Decision decisionOf(DecisionKind kind) {
    Decision d;
    d.kind = kind;
    return d;
}
inline Decision answeredDecision(uint64_t query_frame, const QueryAnswer& answer) {
    Decision d;
    d.kind = answer.visible ? DecisionKind::DrawnOnQuery : DecisionKind::CulledOnQuery;
    d.query_frame = static_cast<uint32_t>(query_frame);
    d.samples = answer.samples > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(answer.samples);
    d.flags = answer.waited ? kDecisionWaited : 0;
    return d;
}
inline Decision inFlightDecision(uint64_t query_frame) {
    Decision d;
    d.kind = DecisionKind::DrawnQueryInFlight;
    d.query_frame = static_cast<uint32_t>(query_frame);
    return d;
}

}  // namespace occsim
