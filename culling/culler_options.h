// Every culler's options as plain data, in one header the rest of the program may see (the
// scenario parser, sweeps, the tuner) without seeing any culler's internals. Each struct's
// isValid() is the one definition of "valid": parsers and sweeps report its message.
#pragma once

#include <cstdint>
#include <string>

namespace occsim {

// What drawing and querying cost on the renderer at hand, in milliseconds: the per-frame cost
// model of the brief's "Cost model" section, in the spirit of the start-up measurements of Guthe,
// Balazs & Klein, "Near Optimal Hierarchical Culling" (EGSR 2006), section 4. Drawing an object
// costs draw_call_ms + triangles * triangle_ms; a query costs query_box_ms per box it rasterises.
// Plain data: measured at start-up by the run layer (sim/run/calibration.h), or given in a
// scenario as culling.cost_model {"query_box_ms", "triangle_ms", "draw_call_ms"}, e.g. by the
// tuner. All zero means "not known": cullers then ignore it.
struct CostModel {
    double query_box_ms = 0.0;
    double triangle_ms = 0.0;
    double draw_call_ms = 0.0;

    bool known() const { return query_box_ms > 0.0 || triangle_ms > 0.0 || draw_call_ms > 0.0; }
    double drawMs(uint64_t triangles) const {
        return draw_call_ms + static_cast<double>(triangles) * triangle_ms;
    }
    // Every figure finite and >= 0.
    bool isValid(std::string* error) const;
    bool operator==(const CostModel&) const = default;
};

// Kovalčík & Sochor, "Occlusion Culling with Statistically Optimized Occlusion Queries", WSCG
// 2005, section 3: BASE_TIME and the decay curve of CalcNodeAction, and the two-queue traversal.
// The first block is the paper; the second holds improvements beyond it, each off by default (so
// that StatisticalOptions{} is the paper as published) and all on in plus() (the "statistical+"
// algorithm). docs/statistical.md says what each does and why.
struct StatisticalOptions {
    double base_time_s = 2.0 / 3.0;      // BASE_TIME
    double decay_a = 2.0;                // a in BASE_TIME * (a - b^occ_num)
    double decay_b = 0.5;                // b in BASE_TIME * (a - b^occ_num)
    uint32_t history_length = 8;         // query results remembered per node (1..32)
    double max_statistics_age_s = 2.0;   // older statistics are ignored: query again
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

    // The paper as published (the default).
    static StatisticalOptions paper() { return {}; }
    // Every improvement on: the "statistical+" algorithm's defaults.
    static StatisticalOptions plus();

    bool isValid(std::string* error) const;
};

// Bittner, Wimmer, Piringer & Purgathofer, "Coherent Hierarchical Culling: Hardware Occlusion
// Queries Made Useful", Eurographics 2004, "Further Optimizations". The paper's approximate
// visibility (n_vp) is the pixel threshold of ApproximationOptions, shared by every culler.
struct ChcOptions {
    // t_av: frames a leaf found visible is assumed visible without a query. 0 = every previously
    // visible leaf is queried every frame (the basic algorithm).
    uint32_t visible_frames_skip = 0;

    bool isValid(std::string* error) const;
};

// Mattausch, Bittner & Wimmer, "CHC++: Coherent Hierarchical Culling Revisited", Eurographics
// 2008, sections 4 (queues), 5.1 (multiqueries), 5.2 (randomised sampling) and 6 (tight bounds).
struct ChcppOptions {
    // n_av: frames a node found visible is assumed visible (no query) before the next test.
    // On the default teapot scenario (llvmpipe), n_av = 0 / 2 / 5 / 10 gives 280 / 176 / 146 /
    // 125 queries and 1004 / 1044 / 1126 / 1197 drawn objects per frame: 2 trades about even.
    uint32_t visible_frames_skip = 2;
    // Previously invisible nodes collected before a batch of queries is issued.
    uint32_t batch_size = 50;
    // Group previously invisible nodes into multiqueries (false: one query per node).
    bool multiqueries = true;
    // Query a node with its descendants' boxes this many levels down; 0 = its own box. On the
    // default teapot scenario 2 saves a few queries and drawn objects at every n_av.
    uint32_t tight_bounds_depth = 2;
    // Seeds the randomised first re-test of nodes that turned visible.
    uint64_t seed = 1;

    bool isValid(std::string* error) const;
};

// The per-object asynchronous scheme of the PURE engine notes ("Simple Pseudo-code"), with the
// re-test rule of the ARB_occlusion_query specification.
struct AsyncOptions {
    // N: a visible object is queried again this many frames after its last query. 1 = every frame.
    uint32_t retest_interval_frames = 5;

    bool isValid(std::string* error) const;
};

// Two ways to trade image error for time, for any culler that issues queries (applied by
// ApproximateDevice, culling/approximate_device.h):
// - threshold_pixels: a query passing at most this many samples counts as occluded (the CHC
//   paper's approximate visibility, n_vp);
// - stale_results: a result not ready when the culler asks for it is taken from the last frame's
//   query on the same boxes instead of waited for.
// Both make conservative cullers approximate; with both off nothing changes.
struct ApproximationOptions {
    uint32_t threshold_pixels = 0;
    bool stale_results = false;

    bool active() const { return threshold_pixels > 0 || stale_results; }
};

struct CullerOptions {
    StatisticalOptions statistical;                                   // "statistical"
    StatisticalOptions statistical_plus = StatisticalOptions::plus();  // "statistical+"
    CostModel cost_model;  // unknown (all zero) unless given or measured at start-up
    ChcOptions chc;
    ChcppOptions chcpp;
    AsyncOptions async;
    ApproximationOptions approximation;

    // The first invalid member's message.
    bool isValid(std::string* error) const;
};

}  // namespace occsim
