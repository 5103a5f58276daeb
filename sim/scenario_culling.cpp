// The "culling" section of a scenario: the algorithm and each algorithm's options. Validation
// that the culling module owns (StatisticalOptions::isValid) is delegated to it.
#include "sim/scenario_parts.h"

#include <limits>

namespace occsim {
namespace {

constexpr uint64_t kMaxUint32 = std::numeric_limits<uint32_t>::max();

StatisticalOptions readStatistical(JsonObjectReader reader) {
    StatisticalOptions o;
    o.base_time_s = reader.number("base_time", o.base_time_s);
    o.decay_a = reader.number("decay_a", o.decay_a);
    o.decay_b = reader.number("decay_b", o.decay_b);
    o.history_length =
        static_cast<uint32_t>(reader.unsignedInteger("history_length", o.history_length, 0,
                                                     kMaxUint32));
    o.max_statistics_age_s = reader.number("max_statistics_age", o.max_statistics_age_s);
    o.queries_before_restart = static_cast<uint32_t>(
        reader.unsignedInteger("queries_before_restart", o.queries_before_restart, 0, kMaxUint32));
    reader.finish();
    std::string why;
    if (!o.isValid(&why)) reader.failHere(why);
    return o;
}

}  // namespace

void readCulling(JsonObjectReader& top, Scenario& s) {
    auto culling = top.optionalObject("culling");
    if (!culling) return;
    s.algorithm = culling->enumeration("algorithm", cullerNames(), s.algorithm);
    if (auto statistical = culling->optionalObject("statistical")) {
        s.culler.statistical = readStatistical(std::move(*statistical));
    }
    culling->finish();
}

}  // namespace occsim
