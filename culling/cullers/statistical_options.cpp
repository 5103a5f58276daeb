#include "culling/cullers/statistical_options.h"

namespace occsim {

StatisticalOptions StatisticalOptions::plus() {
    StatisticalOptions o;
    o.ready_answers = true;
    // With ready answers this is the most queries in flight. On llvmpipe an answer arrives only
    // once everything before it is rasterised, so the fewer queries run ahead of their answers
    // the more depth each one sees (docs/statistical.md has the sweep).
    o.queries_before_restart = 4;
    o.virtual_leaves = true;
    o.object_queries = true;
    o.cost_model = true;
    o.requery_parallax = 0.025;
    o.fallback = true;
    // CHC's treatment of what was visible (drawn at once, inner nodes traversed without a query)
    // and a bound on queries in flight that counts each by its chance of coming back visible:
    // together they took the paper library from 1.47x to 2.05-2.17x over VFC and the plant from
    // 1.07x to 1.42x on a quiet machine (docs/statistical.md, (6)-(8)).
    o.draw_while_requerying = true;
    o.descend_visible_inner_nodes = true;
    o.weigh_in_flight = true;
    // A frame of thousands of waited queries (the library, the plant) blocks about 8 times
    // instead of every 4 in flight: 1.79x -> 1.99x and 1.07x -> 1.16x over VFC there, no scene
    // of the paper or generalisation sets slower beyond the spread (docs/statistical.md, (9)).
    o.waits_per_frame = 8;
    // requery_horizon (10) stays off: on the default teapots it cost 3 to 5 % (the ablation of
    // 2026-12-04, docs/statistical.md), on the levels it saved 2 to 5 % of the triangles at equal
    // times.
    // Nearest first: on the street canyon 37.8K -> 22.8K triangles a frame (ideal-box 21.9K), the
    // props behind the buildings no longer queried before them (docs/statistical.md, (11)).
    o.distance_order = true;
    return o;
}

bool StatisticalOptions::isValid(std::string* error) const {
    if (requery_distance_m > 0.0 && requery_parallax > 0.0) {
        if (error)
            *error = "requery_distance and requery_parallax are alternatives: set at most one";
        return false;
    }
    return true;
}

}  // namespace occsim
