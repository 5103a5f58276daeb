// Occlusion culling with statistically optimised occlusion queries (Kovalčík & Sochor, WSCG 2005).
//
// Each node keeps the results of its recent queries. CalcNodeAction decides per node:
//   frustum-culled                              -> SKIP
//   near plane may cut its box (viewer inside)  -> RENDER (a clipped query could lie)
//   no statistics, or statistics too old        -> QUERY
//   last query said occluded                    -> QUERY
//   now > last_query_time + BASE_TIME * (a - b^occ_num)  -> QUERY
//   otherwise                                   -> RENDER without a query
// where occ_num is the number of unoccluded results in the node's history ("the decay curve";
// the paper uses a = 2, b = 0.5, BASE_TIME = 2/3 s). Time is simulation time.
//
// The traversal is the paper's two-queue scheme. The main queue holds nodes in front-to-back
// order of the tree: a node rendered without a query is replaced by its children, nearer child
// first ("placed in the queue at the position of the deleted node"); a queried node goes to the
// query queue, and the loop moves on without waiting. It stops when the oldest query's answer is
// ready (or after `queries_before_restart` queries), then takes every pending answer in issue
// order, and the children of the visible ones go back to the start of the main queue in that
// order, each node's nearer child first ("AddChildrenBeforePointer"). Both rules keep the main
// queue in the front-to-back depth-first order of the tree, so it is kept as a min-heap on each
// entry's rank in that order: nodes are taken nearest first, however answers arrive.
//
// StatisticalOptions holds improvements beyond the paper, each off by default (the paper as
// published) and, but for the last, on in "statistical+": answers taken as they become ready (with
// a bound on the queries in flight), virtual leaves for the objects stored in inner nodes,
// decisions per object, a cost model, re-query after a distance travelled, a fallback to frustum
// culling when little is occluded, CHC's treatment of what was visible, a bound on queries in
// flight that weighs each by its chance of coming back visible and grows with the frame's queries,
// the main queue taken nearest first by distance (the loose tree's depth-first order is not a
// visibility order), and re-queries of what was visible weighed over the frames their answers
// decide. docs/statistical.md describes them and why.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "culling/cullers/statistical_options.h"
#include "occsim/culling/contract/cost_model.h"
#include "occsim/culling/contract/culler.h"
#include "occsim/culling/declaration/option_table.h"
#include "occsim/culling/tree/node_state.h"
#include "occsim/culling/tree/traversal.h"

namespace occsim {

// What CalcNodeAction decides for a node that passed the frustum test (the paper's SKIP is the
// frustum test itself, made by the traversal before it asks).
enum class NodeAction : uint8_t { Render, Query };

struct NodeStatistics {
    double last_query_time_s = 0.0;
    // The node's travel counter (camera path plus its movers' motion, metres) at its last query;
    // only the distance rules (requery_distance_m, requery_parallax) read it.
    double travel_at_query_m = 0.0;
    // When (and at which travel counter) the cost model last put off a query the interval asked
    // for: the interval runs again from there. 0 = never (both clocks start at 0).
    double deferred_time_s = 0.0;
    double deferred_travel_m = 0.0;
    uint32_t history = 0;           // bit i = result of the i-th most recent query (1 = visible)
    uint8_t results = 0;            // how many results the history holds (<= history_length)
    uint32_t last_query_frame = 0;  // the frame its last answered query was issued in
};

// Where a node is, for the distance rules of CalcNodeAction (improvement 4): its travel counter
// now (metres, only differences matter) and its distance from the eye.
struct NodeMotion {
    double travel_m = 0.0;
    double distance_m = 0.0;
};

// The options table of "statistical" and "statistical+" (statistical_registration.cpp): its
// read() turns either culler's option values into StatisticalOptions.
const OptionTable<StatisticalOptions>& statisticalOptionTable();

// CalcNodeAction's re-query interval for statistics whose last result was visible: the decay
// curve's BASE_TIME * (a - b^occ_num) (seconds), or with the distance rules the distance to
// travel (metres), counted from `since` (a time, or the node's travel counter).
struct RequeryInterval {
    double interval = 0.0;
    double since = 0.0;
    bool distance = false;    // interval and since are metres
    int visible_results = 0;  // occ_num
};
RequeryInterval requeryInterval(const StatisticalOptions& options, const NodeStatistics& stats,
                                NodeMotion motion = {});

// Improvement (10): the frames a re-query's answer decides, for a subject last found visible
// whose interval is `r`: the interval at this frame's rate of advance (`step` metres of travel
// with the distance rules, `dt_s` seconds otherwise), at least 1 and at most the frames before
// statistics grow too old (max_statistics_age_s). dt_s <= 0 (the first frame) gives 1.
double requeryHorizonFrames(const StatisticalOptions& options, const RequeryInterval& r,
                            double step_m, double dt_s);

// CalcNodeAction for a node that passed the frustum test; exposed for tests and the tuner.
NodeAction decideNodeAction(const StatisticalOptions& options, const NodeStatistics& stats,
                            bool near_plane_touches_box, double now_s, NodeMotion motion = {});

// Records one query result into a node's history.
void recordQueryResult(const StatisticalOptions& options, NodeStatistics& stats, bool visible,
                       double now_s, double travel_m = 0.0);

// What a node's statistics say about the query CalcNodeAction asks for: its last result, or none.
// Queries with each prior result have their own recent occlusion rate in the cost model
// (improvement 3), kept over the answers to those queries.
enum class PriorResult : uint8_t {
    Fresh,         // no statistics yet
    LastVisible,   // the last result was visible (the re-query interval ran out, or too old)
    LastOccluded,  // the last result was occluded
};
PriorResult priorResultOf(const NodeStatistics& stats);
// Statistics exist and are not older than max_statistics_age_s.
bool statisticsUsable(const StatisticalOptions& options, const NodeStatistics& stats, double now_s);

// The cost model's estimate of how likely a query of one kind finds its subject occluded: the
// running mean of the answers to such queries (1 = occluded). A kind whose queries the cost
// model keeps putting off would never be measured again, so every kExploreEvery-th query it
// would put off on the estimate's word is issued anyway (a fixed count, so decisions stay
// deterministic), which keeps the estimate current.
struct OcclusionEstimate {
    static constexpr uint32_t kExploreEvery = 8;
    double occluded = 0.5;
    uint32_t vetoes = 0;  // vetoes since the last one that was issued anyway
    void add(bool was_occluded);
};

// The cost model's rule (improvement 3): a query pays when its expected saving, the chance it
// finds the node occluded times the node's draw cost, exceeds the query's own cost. A node
// cheaper to draw than to query never pays (the chance is at most 1, which is what the culler
// assumes for a node without usable statistics).
bool queryPays(const CostModel& costs, double draw_ms, uint32_t query_boxes, double occlusion_rate);

// What the last frame did, for tests and reports.
struct StatisticalFrameCounters {
    uint32_t queries = 0;
    uint32_t answers = 0;
    uint32_t visible_answers = 0;
    uint32_t renders_without_query = 0;  // CalcNodeAction said RENDER (near plane included)
    uint32_t cost_model_renders = 0;     // CalcNodeAction said QUERY, the cost model RENDER
    uint32_t blocked_answers = 0;        // answers taken before they were ready
    // ... while the culler could have gone on instead: the main queue held entries and (with
    // ready_answers) fewer than queries_before_restart queries were in flight.
    uint32_t blocked_with_work_left = 0;
    double in_flight_bound = 0.0;  // with ready_answers: the bound on queries in flight used
    uint32_t update_queries = 0;   // draw_while_requerying: queries whose answer only updates
    uint32_t inner_descents = 0;   // descend_visible_inner_nodes: re-queries not issued
    bool frustum_only = false;     // a fallback frame (improvement 5)
};

class StatisticalCuller final : public Culler {
  public:
    explicit StatisticalCuller(const StatisticalOptions& options = {}, const CostModel& costs = {});
    void reset(const BspTree& tree) override;
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override;

    const StatisticalOptions& options() const { return options_; }
    const CostModel& costModel() const { return costs_; }
    const NodeStatistics& statistics(uint32_t node) const { return stats_[node]; }
    // The statistics of the objects stored in an inner node itself (its virtual leaf).
    const NodeStatistics& ownObjectStatistics(uint32_t node) const { return own_stats_[node]; }
    // The statistics of one object (object_queries).
    const NodeStatistics& objectStatistics(uint32_t object) const { return object_stats_[object]; }
    const StatisticalFrameCounters& lastFrame() const { return counters_; }
    // The cost model's occlusion estimate of each PriorResult, for queries on nodes (and virtual
    // leaves) and on single objects.
    const OcclusionEstimate& occlusionEstimate(PriorResult prior, bool object_query = false) const {
        return estimates_[estimateIndex(prior, object_query)];
    }

  private:
    // What an entry decides is what a query on it decides (QueryTag::Subject): a node's subtree,
    // the objects stored in an inner node itself (its virtual leaf), or one object
    // (object_queries; only ever a pending query, never queued).
    using Subject = QueryTag::Subject;
    // An entry of the main queue, or what a pending query is about. `index` is a node, or an
    // object for Subject::Object. `rank` is the entry's place in the front-to-back depth-first
    // order of the tree for this frame's eye, or with distance_order the bit pattern of the
    // squared distance from the eye to its bounds (which orders as the distance does).
    struct Entry {
        uint32_t rank;
        uint32_t index;
        Subject subject;
        bool inside_frustum;
    };
    // What decide() found besides the action, kept with a query until its answer.
    struct QueryContext {
        PriorResult prior = PriorResult::Fresh;
    };
    struct Pending {
        QueryId id;
        Entry entry;
        QueryContext context;
        double weight;  // what it counts against the bound on queries in flight (weigh_in_flight)
    };
    // A query whose answer only updates statistics (draw_while_requerying): the subject was
    // drawn when it was issued. Kept across frames until its answer is taken; `generation` is
    // the node's at issue time, so an answer for a node the tree has since replaced is dropped.
    struct Update {
        QueryId id;
        Entry entry;
        QueryContext context;
        double time_s;
        double travel_m;
        uint32_t generation;
        uint64_t frame;
    };
    struct Motion {  // cumulative motion of a node's movers (metres), for the distance rules
        double subtree_m = 0.0;
        double own_m = 0.0;
    };

    void syncStructure(const BspTree& tree);
    void prepareFrame(const BspTree& tree, const CullFrame& frame);
    void frustumOnlyFrame(const BspTree& tree, RenderDevice& device);
    void endFrame(double now_s);

    void push(const Entry& entry);
    Entry pop();
    void pushChildren(const BspTree& tree, const CullFrame& frame, uint32_t node, uint32_t rank,
                      bool inside_frustum);
    // Returns true when it issued a query.
    bool process(const BspTree& tree, const CullFrame& frame, Entry entry, RenderDevice& device);
    // Draws the objects stored in `node` itself that pass the frustum, or, with object_queries,
    // decides each on its own statistics. Returns the number of queries issued.
    uint32_t renderObjects(const BspTree& tree, const CullFrame& frame, uint32_t node,
                           bool inside_frustum, RenderDevice& device, const Decision& why);
    // CalcNodeAction and the cost model for one subject; counts the decision. When it says Render,
    // `why` says on what (the near plane, the statistics, the cost model).
    NodeAction decide(const CullFrame& frame, NodeStatistics& stats, const Aabb& box,
                      const Entry& subject, double draw_ms, uint32_t query_boxes,
                      QueryContext* context, Decision* why);
    // Takes the pending query's answer and acts on it; returns whether the device waited for it.
    bool answer(const BspTree& tree, const CullFrame& frame, const Pending& pending,
                RenderDevice& device);
    double inFlightBound() const;
    // Puts an issued query into the query queue with its weight against the in-flight bound.
    void enqueue(QueryId id, const Entry& entry, const QueryContext& context);
    // Draw-while-requerying: issues the query whose answer only updates statistics.
    void issueUpdate(const BspTree& tree, const CullFrame& frame, const Entry& entry,
                     std::span<const Aabb> boxes, const QueryTag& tag, const QueryContext& context,
                     RenderDevice& device);
    // Takes the ready update answers in issue order; with `older_than_frame`, also waits for
    // those issued before that frame.
    void collectUpdates(const BspTree& tree, RenderDevice& device, uint64_t older_than_frame);
    void record(const Entry& e, const QueryContext& context, bool visible, double time_s,
                double travel_m, uint64_t frame);
    // A rendered node (its own objects drawn for `why`, or queued as a virtual leaf) and its
    // children queued.
    void renderNode(const BspTree& tree, const CullFrame& frame, const Entry& entry,
                    RenderDevice& device, const Decision& why);
    // DrawnOnStatistics with what the statistics said (the last query, the interval).
    Decision statisticsDecision(const NodeStatistics& stats, const NodeMotion& motion) const;
    // A decision on a queue entry's subject: a node's subtree, a virtual leaf, or an object.
    void recordFor(const Entry& e, const Decision& why) const {
        recordDecision(view_.decisions, QueryTag{e.subject, e.index}, why);
    }
    NodeStatistics& statsOf(const Entry& e);
    double travelOf(const Entry& e) const;
    // How far the subject's travel counter advanced this frame (distance rules): the camera's
    // step plus the largest step of its movers.
    double stepOf(const Entry& e) const;
    bool drawsWhileRequerying(const QueryContext& context) const {
        return options_.draw_while_requerying && context.prior == PriorResult::LastVisible;
    }
    static size_t estimateIndex(PriorResult prior, bool object_query) {
        return static_cast<size_t>(prior) + (object_query ? 3 : 0);
    }

    StatisticalOptions options_;
    PreparedView view_;  // this frame's view with its plane table (prepareView)
    CostModel costs_;

    NodeStateArray<NodeStatistics> stats_;
    NodeStateArray<NodeStatistics> own_stats_;
    NodeStateArray<Motion> motion_;
    std::vector<NodeStatistics> object_stats_;  // per object (object_queries)
    std::vector<double> object_motion_m_;       // per object, cumulative (distance rules)
    std::vector<float> object_step_m_;          // per object, this frame's step (distance rules)

    // The tree's structure as last seen: nodes in depth-first order and the number of ranks each
    // subtree spans (a node, its virtual leaf if inner, and its children's subtrees).
    uint64_t structure_version_ = 0;
    bool structure_known_ = false;
    std::vector<uint32_t> order_;
    std::vector<uint32_t> subtree_ranks_;
    std::vector<uint32_t> scratch_stack_;

    // Per frame.
    bool costs_active_ = false;
    std::vector<double> subtree_draw_ms_;  // cost model: drawing every object of the subtree
    std::vector<float> step_m_;            // distance rules: this frame's largest mover step
    std::vector<float> own_step_m_;        // ... of the objects stored in the node itself
    std::vector<glm::vec3> last_center_;   // distance rules: object centres last frame
    glm::vec3 last_eye_{0.0f};
    bool have_last_frame_ = false;
    double camera_path_m_ = 0.0;
    double camera_step_m_ = 0.0;  // this frame's part of camera_path_m_
    double last_time_s_ = 0.0;    // the last frame's time, for dt_s_ (requery_horizon)
    double dt_s_ = 0.0;           // simulation time since the last frame; NaN in the first

    std::vector<Entry> heap_;       // the main queue (min-heap on rank)
    std::vector<Pending> pending_;  // the query queue: [pending_head_, size) in flight
    std::vector<Update> updates_;   // draw_while_requerying: [updates_head_, size) in flight
    size_t updates_head_ = 0;
    size_t pending_head_ = 0;
    double in_flight_weight_ = 0.0;  // the weights of [pending_head_, size)
    // waits_per_frame: the weights of this frame's waited queries so far, and the last frame's.
    double waited_weight_ = 0.0;
    double last_waited_weight_ = 0.0;
    std::vector<Aabb> boxes_;  // scratch: a virtual leaf's boxes
    std::vector<NodeVisit> vfc_stack_;

    std::array<OcclusionEstimate, 6> estimates_{};  // per PriorResult, node then object queries

    // Fallback (improvement 5): answers and visible answers of the last frames, in a ring.
    std::vector<uint32_t> window_answers_;
    std::vector<uint32_t> window_visible_;
    uint32_t window_next_ = 0;
    uint32_t window_frames_ = 0;
    double frustum_only_until_s_ = 0.0;
    bool frustum_only_ = false;

    StatisticalFrameCounters counters_;
};

}  // namespace occsim
