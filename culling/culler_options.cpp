#include "culling/culler_options.h"

#include <cmath>

namespace occsim {
namespace {

// Far beyond any useful setting; keeps frame arithmetic far from overflow.
constexpr uint32_t kMaxFramesSkip = 1000000;
constexpr uint32_t kMaxTightBoundsDepth = 6;  // up to 2^6 boxes (plus straddler boxes) per node
constexpr uint32_t kMaxRetestInterval = 1000000;
constexpr uint32_t kMaxFallbackWindow = 1000;

bool fail(std::string* error, const char* message) {
    if (error) *error = message;
    return false;
}

}  // namespace

bool StatisticalOptions::isValid(std::string* error) const {
    if (!(std::isfinite(base_time_s) && base_time_s >= 0.0))
        return fail(error, "base_time_s must be a finite number >= 0 (seconds)");
    if (!(std::isfinite(decay_a) && std::isfinite(decay_b)))
        return fail(error, "decay_a and decay_b must be finite numbers");
    if (!(decay_b >= 0.0 && decay_b <= 1.0)) return fail(error, "decay_b must be in [0, 1]");
    if (!(decay_a >= 1.0))
        return fail(error, "decay_a must be >= 1 so that the re-query interval is never negative");
    if (history_length < 1 || history_length > 32)
        return fail(error, "history_length must be in [1, 32]");
    if (!(std::isfinite(max_statistics_age_s) && max_statistics_age_s > 0.0))
        return fail(error, "max_statistics_age_s must be a finite number > 0 (seconds)");
    if (queries_before_restart < 1) return fail(error, "queries_before_restart must be >= 1");
    if (!(std::isfinite(requery_distance_m) && requery_distance_m >= 0.0))
        return fail(error, "requery_distance must be a finite number >= 0 (metres; 0 = off)");
    if (!(std::isfinite(requery_parallax) && requery_parallax >= 0.0))
        return fail(error, "requery_parallax must be a finite number >= 0 (0 = off)");
    if (requery_distance_m > 0.0 && requery_parallax > 0.0)
        return fail(error, "requery_distance and requery_parallax are alternatives: set at most one");
    if (!(fallback_visible_share >= 0.0 && fallback_visible_share <= 1.0))
        return fail(error, "fallback_visible_share must be in [0, 1]");
    if (fallback_window_frames < 1 || fallback_window_frames > kMaxFallbackWindow)
        return fail(error, "fallback_window_frames must be in [1, 1000] (frames)");
    if (!(std::isfinite(fallback_recheck_s) && fallback_recheck_s >= 0.0))
        return fail(error, "fallback_recheck must be a finite number >= 0 (seconds)");
    return true;
}

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
    return o;
}

bool CostModel::isValid(std::string* error) const {
    for (double v : {query_box_ms, triangle_ms, draw_call_ms}) {
        if (!(std::isfinite(v) && v >= 0.0)) {
            return fail(error, "query_box_ms, triangle_ms and draw_call_ms must be finite numbers "
                               ">= 0 (milliseconds)");
        }
    }
    return true;
}

bool ChcOptions::isValid(std::string* error) const {
    if (visible_frames_skip > kMaxFramesSkip) {
        return fail(error, "visible_frames_skip must be in [0, 1000000] (frames)");
    }
    return true;
}

bool ChcppOptions::isValid(std::string* error) const {
    if (visible_frames_skip > kMaxFramesSkip) {
        return fail(error, "visible_frames_skip must be in [0, 1000000] (frames)");
    }
    if (batch_size < 1) return fail(error, "batch_size must be >= 1 (nodes)");
    if (tight_bounds_depth > kMaxTightBoundsDepth) {
        return fail(error, "tight_bounds_depth must be in [0, 6] (levels; 0 = the node's own box)");
    }
    return true;
}

bool AsyncOptions::isValid(std::string* error) const {
    if (retest_interval_frames < 1 || retest_interval_frames > kMaxRetestInterval) {
        return fail(error, "retest_interval_frames must be in [1, 1000000] (frames)");
    }
    return true;
}

bool CullerOptions::isValid(std::string* error) const {
    return statistical.isValid(error) && statistical_plus.isValid(error) &&
           cost_model.isValid(error) && chc.isValid(error) && chcpp.isValid(error) &&
           async.isValid(error);
}

}  // namespace occsim
