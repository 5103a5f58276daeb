// The "culling" section of a scenario: the algorithm and each algorithm's options. Validation
// that the culling module owns (StatisticalOptions::isValid, ChcOptions::isValid, ...) is
// delegated to it; its message is reported at the options object's pointer.
#include "sim/scenario/parser_parts.h"

#include "culling/algorithms.h"

#include <limits>

namespace occsim {
namespace {

constexpr uint64_t kMaxUint32 = std::numeric_limits<uint32_t>::max();

// The same keys for "statistical" and "statistical+"; only the defaults differ (the paper's, or
// every improvement on).
StatisticalOptions readStatistical(JsonObjectReader reader, const StatisticalOptions& defaults) {
    StatisticalOptions o = defaults;
    o.base_time_s = reader.number("base_time", o.base_time_s);
    o.decay_a = reader.number("decay_a", o.decay_a);
    o.decay_b = reader.number("decay_b", o.decay_b);
    o.history_length =
        static_cast<uint32_t>(reader.unsignedInteger("history_length", o.history_length, 0,
                                                     kMaxUint32));
    o.max_statistics_age_s = reader.number("max_statistics_age", o.max_statistics_age_s);
    o.queries_before_restart = static_cast<uint32_t>(
        reader.unsignedInteger("queries_before_restart", o.queries_before_restart, 0, kMaxUint32));
    o.ready_answers = reader.boolean("ready_answers", o.ready_answers);
    o.virtual_leaves = reader.boolean("virtual_leaves", o.virtual_leaves);
    o.object_queries = reader.boolean("object_queries", o.object_queries);
    o.cost_model = reader.boolean("cost_model", o.cost_model);
    o.requery_distance_m = reader.number("requery_distance", o.requery_distance_m);
    o.requery_parallax = reader.number("requery_parallax", o.requery_parallax);
    o.fallback = reader.boolean("fallback", o.fallback);
    o.fallback_visible_share = reader.number("fallback_visible_share", o.fallback_visible_share);
    o.fallback_window_frames = static_cast<uint32_t>(
        reader.unsignedInteger("fallback_window_frames", o.fallback_window_frames, 0, kMaxUint32));
    o.fallback_recheck_s = reader.number("fallback_recheck", o.fallback_recheck_s);
    reader.finish();
    std::string why;
    if (!o.isValid(&why)) reader.failHere(why);
    return o;
}

// What drawing and querying cost (milliseconds); the tuner writes it, or calibration measures it.
CostModel readCostModel(JsonObjectReader reader) {
    CostModel c;
    c.query_box_ms = reader.number("query_box_ms", c.query_box_ms);
    c.triangle_ms = reader.number("triangle_ms", c.triangle_ms);
    c.draw_call_ms = reader.number("draw_call_ms", c.draw_call_ms);
    reader.finish();
    std::string why;
    if (!c.isValid(&why)) reader.failHere(why);
    if (!c.known()) reader.failHere("a cost model needs at least one figure > 0 (milliseconds)");
    return c;
}

// Counts that the culling module keeps as uint32_t: anything larger is a type error here, and
// the range within uint32_t is isValid()'s to judge.
uint32_t readCount(JsonObjectReader& reader, std::string_view key, uint32_t fallback) {
    return static_cast<uint32_t>(reader.unsignedInteger(key, fallback, 0, kMaxUint32));
}

ChcOptions readChc(JsonObjectReader reader) {
    ChcOptions o;
    o.visible_frames_skip = readCount(reader, "visible_frames_skip", o.visible_frames_skip);
    reader.finish();
    std::string why;
    if (!o.isValid(&why)) reader.failHere(why);
    return o;
}

ChcppOptions readChcpp(JsonObjectReader reader) {
    ChcppOptions o;
    o.visible_frames_skip = readCount(reader, "visible_frames_skip", o.visible_frames_skip);
    o.batch_size = readCount(reader, "batch_size", o.batch_size);
    o.multiqueries = reader.boolean("multiqueries", o.multiqueries);
    o.tight_bounds_depth = readCount(reader, "tight_bounds_depth", o.tight_bounds_depth);
    o.seed = reader.unsignedInteger("seed", o.seed);
    reader.finish();
    std::string why;
    if (!o.isValid(&why)) reader.failHere(why);
    return o;
}

AsyncOptions readAsync(JsonObjectReader reader) {
    AsyncOptions o;
    o.retest_interval_frames =
        readCount(reader, "retest_interval_frames", o.retest_interval_frames);
    reader.finish();
    std::string why;
    if (!o.isValid(&why)) reader.failHere(why);
    return o;
}

}  // namespace

void readCulling(JsonObjectReader& top, Scenario& s) {
    auto culling = top.optionalObject("culling");
    if (!culling) return;
    s.algorithm = culling->enumeration("algorithm", algorithmNames(), s.algorithm);
    // The approximation knobs, shared by every query-based algorithm (culler_options.h).
    s.culler.approximation.threshold_pixels =
        readCount(*culling, "threshold_pixels", s.culler.approximation.threshold_pixels);
    s.culler.approximation.stale_results =
        culling->boolean("stale_results", s.culler.approximation.stale_results);
    if (auto statistical = culling->optionalObject("statistical")) {
        s.culler.statistical = readStatistical(std::move(*statistical), StatisticalOptions::paper());
    }
    if (auto plus = culling->optionalObject("statistical+")) {
        s.culler.statistical_plus = readStatistical(std::move(*plus), StatisticalOptions::plus());
    }
    if (auto costs = culling->optionalObject("cost_model")) {
        s.culler.cost_model = readCostModel(std::move(*costs));
    }
    if (auto chc = culling->optionalObject("chc")) s.culler.chc = readChc(std::move(*chc));
    if (auto chcpp = culling->optionalObject("chc++")) {
        s.culler.chcpp = readChcpp(std::move(*chcpp));
    }
    if (auto async = culling->optionalObject("async")) {
        s.culler.async = readAsync(std::move(*async));
    }
    culling->finish();
}

}  // namespace occsim
