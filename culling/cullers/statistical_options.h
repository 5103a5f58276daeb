// The statistical culler's options as plain data (the culler reads these; scenarios, sweeps and
// the tuner set them through the descriptor of statisticalDescriptor(), statistical_culler.h).
#pragma once

#include <cstdint>
#include <string>

namespace occsim {

// Kovalčík & Sochor, "Occlusion Culling with Statistically Optimized Occlusion Queries", WSCG
// 2005, section 3: BASE_TIME and the decay curve of CalcNodeAction, and the two-queue traversal.
// The first block is the paper; the second holds improvements beyond it, each off by default (so
// that StatisticalOptions{} is the paper as published) and on in plus() (the "statistical+"
// algorithm) but for requery_horizon, measured not to pay. docs/statistical.md says what each
// does and why.
struct StatisticalOptions {
    double base_time_s = 2.0 / 3.0;        // BASE_TIME
    double decay_a = 2.0;                  // a in BASE_TIME * (a - b^occ_num)
    double decay_b = 0.5;                  // b in BASE_TIME * (a - b^occ_num)
    uint32_t history_length = 8;           // query results remembered per node (1..32)
    double max_statistics_age_s = 2.0;     // older statistics are ignored: query again
    uint32_t queries_before_restart = 20;  // return to the queue start after this many queries

    // (1) Take each answer as soon as it is ready and keep traversing; block on the oldest
    // answer only when nothing else can be done: the queue is empty, or queries_before_restart
    // queries are in flight (the paper's bound on how far the traversal runs ahead of its
    // answers). Off: the paper's passes (issue until the oldest answer is ready or
    // queries_before_restart were issued, then take every pending answer, ready or not).
    bool ready_answers = false;
    // (2) The objects stored in an inner node itself get statistics and queries of their own
    // (a "virtual leaf": a query on the boxes of those objects). Off: they are drawn whenever
    // their node is rendered, as the paper does (it keeps geometry in leaves).
    bool virtual_leaves = false;
    // (2b) The objects of a rendered node (a leaf's, or a virtual leaf's) are decided one by one,
    // each with statistics and queries of its own, instead of drawn (or queried) together. A
    // leaf holding a single object needs no more than its own query.
    bool object_queries = false;
    // (3) Use CullerOptions::cost_model: a node cheaper to draw than to query is drawn without
    // one, and a query is issued only when its expected saving (the recent occlusion rate of
    // such queries times the node's draw cost) exceeds its cost.
    bool cost_model = false;
    // (4) Re-query after a distance travelled instead of BASE_TIME seconds. The travel of a
    // node since its last query is the camera's path plus, for a node holding movers, the
    // farthest any of them moved. requery_distance_m > 0: re-query once the travel exceeds
    // requery_distance_m * (a - b^occ_num) metres. requery_parallax > 0: once the travel divided
    // by the node's distance from the eye (roughly the angle its view turned through) exceeds
    // requery_parallax * (a - b^occ_num), which needs no scene scale. At most one is > 0;
    // both 0 = the paper's seconds.
    double requery_distance_m = 0.0;
    double requery_parallax = 0.0;
    // (5) When the recent answers show little occlusion (at least fallback_visible_share of the
    // answers of the last fallback_window_frames frames came back visible), stop querying and
    // cull by the frustum only for fallback_recheck_s seconds (simulation time), then look again.
    bool fallback = false;
    double fallback_visible_share = 0.9;
    uint32_t fallback_window_frames = 8;
    double fallback_recheck_s = 1.0;
    // (6) A subject whose last answer was visible and whose re-query is due is drawn at once and
    // queried in the same pass, as CHC does with previously visible leaves; its answer, taken
    // when it is ready (in this frame or a later one), only updates its statistics. Off: the
    // paper's culler waits for that answer before it draws the subject. Subjects without
    // statistics, or whose last answer was occluded, are still queried and waited for.
    bool draw_while_requerying = false;
    // (7) With ready_answers, the bound on queries in flight counts each query by its chance of
    // coming back visible (the running visible share of the answers to its kind of query, the
    // estimate the cost model keeps) instead of as one: queries on subjects last found occluded,
    // whose answers rarely draw anything, do not hold the traversal back, while those likely
    // visible, whose late answers let farther nodes be queried against a depth buffer that
    // misses them, do. A query counts at least 1 / kMaxRunAhead, so at most kMaxRunAhead *
    // queries_before_restart are in flight. Off: each query counts as one.
    bool weigh_in_flight = false;
    // (8) An inner node last found visible whose re-query is due is not queried: its subtree is
    // traversed and its children decide, as CHC pulls an inner node's visibility up from its
    // leaves instead of querying it. The re-query interval starts again from now; once the
    // statistics are older than max_statistics_age_s the node is queried afresh. Leaves, virtual
    // leaves and single objects are decided as before (with draw_while_requerying, drawn at once
    // and queried in the same pass). Off: the paper re-queries inner nodes like leaves.
    bool descend_visible_inner_nodes = false;
    static constexpr double kMaxRunAhead = 8.0;
    // (9) With ready_answers, the bound on queries in flight grows with the frame's work: it is
    // at least the queries the last frame waited for (weighed as the bound counts them) divided
    // by waits_per_frame, so that a frame of thousands of such queries blocks about that many
    // times instead of once every queries_before_restart of them, while a frame of few keeps
    // queries_before_restart. A count, not a time: decisions stay deterministic. 0 = off: the
    // bound is queries_before_restart.
    uint32_t waits_per_frame = 0;
    // (10) With cost_model, the re-query of a subject last found visible is weighed over the
    // frames its answer decides, not one: the saving of finding it hidden is its draw cost over
    // the frames until its interval would come due again (the interval in frames at the rate the
    // subject's travel counter, or time, advanced this frame; at most the frames before its
    // statistics grow too old). A heavy prop hidden behind a wall is drawn for every one of those
    // frames when its re-query is put off, so one frame's saving undervalues the query by that
    // many times. Off: rule 2 weighs one frame's draw cost, as for every other query.
    bool requery_horizon = false;
    // (11) The main queue takes its entries nearest first by the distance from the eye to their
    // bounds (as CHC's traversal does), instead of in the tree's depth-first order. The tree's
    // cells are loose: an object belongs to the side of a split its centre is on, and its box
    // reaches across. So a building filed beyond a split can hide a prop filed before it, and in
    // the depth-first order that prop is queried before the building is drawn, against a depth
    // buffer without it: the answer says visible, and the prop is drawn for a whole re-query
    // interval while hidden. Off: the paper's order (children placed where their parent was).
    bool distance_order = false;

    // The paper as published (the default).
    static StatisticalOptions paper() { return {}; }
    // Every improvement on: the "statistical+" algorithm's defaults.
    static StatisticalOptions plus();

    bool operator==(const StatisticalOptions&) const = default;

    // A distance rule (4) replaces BASE_TIME seconds.
    bool requeriesByDistance() const { return requery_distance_m > 0.0 || requery_parallax > 0.0; }

    // The rule that ties options together (each option's own range is the descriptor's,
    // statisticalDescriptor()): at most one of the two re-query distances.
    bool isValid(std::string* error) const;
};

}  // namespace occsim
