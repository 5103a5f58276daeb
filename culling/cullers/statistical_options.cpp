#include "occsim/culling/cullers/statistical_options.h"

namespace occsim {

StatisticalOptions StatisticalOptions::plus() {
    StatisticalOptions o;
    o.ready_answers = true;
    // With ready answers this is the most queries in flight (weighed by weigh_in_flight). On
    // llvmpipe an answer arrives only once everything before it is rasterised: too few in flight
    // and the culler blocks on answers, too many and farther nodes are queried before the nearer
    // ones that hide them are drawn. 16 against 4, quiet machine, two runs each: library 2.14-2.18x
    // against 2.02-2.04x, plant 1.21-1.25x against 1.10-1.19x, teapots 3.64-3.83x against
    // 3.26-3.53x, city 5.27-5.55x against 4.85-5.26x (docs/statistical.md, (1)).
    o.queries_before_restart = 16;
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
