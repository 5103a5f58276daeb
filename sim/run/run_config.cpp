#include "sim/run/run_config.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>

namespace occsim {
namespace {

// Algorithms whose decisions come from occlusion queries: the approximation knobs apply to them.
bool issuesQueries(const AlgorithmTraits& a) { return a.issues_queries; }
bool isStatistical(const AlgorithmTraits& a) {
    return a.family == AlgorithmFamily::Statistical || a.family == AlgorithmFamily::StatisticalPlus;
}
bool isStatisticalPlus(const AlgorithmTraits& a) { return a.family == AlgorithmFamily::StatisticalPlus; }
bool isAsync(const AlgorithmTraits& a) { return a.family == AlgorithmFamily::Async; }

struct Knob {
    SweepParameter parameter;
    double min, max;
    bool integer;
    bool (*applies)(const AlgorithmTraits& algorithm);
    std::function<void(CullerOptions&, double)> set;
};

const std::vector<Knob>& knobs() {
    static const std::vector<Knob> all = {
        {{"threshold", "pixels; a query passing at most this many samples counts as occluded (all query-based algorithms)"},
         0, 1e9, true, issuesQueries,
         [](CullerOptions& c, double v) { c.approximation.threshold_pixels = static_cast<uint32_t>(v); }},
        {{"stale", "0 or 1; 1 = results not ready when needed are taken from the previous frame instead of waited for (all query-based algorithms)"},
         0, 1, true, issuesQueries,
         [](CullerOptions& c, double v) { c.approximation.stale_results = v != 0.0; }},
        // The paper's knobs apply to both statistical cullers (each configuration runs one).
        {{"base_time", "seconds; BASE_TIME of the statistical cullers"}, 0, 1e6, false,
         isStatistical, [](CullerOptions& c, double v) {
             c.statistical.base_time_s = v;
             c.statistical_plus.base_time_s = v;
         }},
        {{"decay_a", "a in BASE_TIME * (a - b^occ_num), statistical cullers"}, 1, 1e6, false,
         isStatistical, [](CullerOptions& c, double v) {
             c.statistical.decay_a = v;
             c.statistical_plus.decay_a = v;
         }},
        {{"decay_b", "b in BASE_TIME * (a - b^occ_num), statistical cullers"}, 0, 1, false,
         isStatistical, [](CullerOptions& c, double v) {
             c.statistical.decay_b = v;
             c.statistical_plus.decay_b = v;
         }},
        {{"restart", "queries; queries_before_restart of the statistical cullers (statistical+: the most queries in flight)"},
         1, 1e6, true, isStatistical, [](CullerOptions& c, double v) {
             c.statistical.queries_before_restart = static_cast<uint32_t>(v);
             c.statistical_plus.queries_before_restart = static_cast<uint32_t>(v);
         }},
        {{"requery_parallax", "statistical+: re-query after travel / distance exceeds this times (a - b^occ_num); 0 = BASE_TIME seconds"},
         0, 1e6, false, isStatisticalPlus, [](CullerOptions& c, double v) {
             c.statistical_plus.requery_parallax = v;
             if (v > 0.0) c.statistical_plus.requery_distance_m = 0.0;
         }},
        {{"requery_distance", "metres; statistical+: re-query after this distance travelled times (a - b^occ_num); 0 = BASE_TIME seconds"},
         0, 1e6, false, isStatisticalPlus, [](CullerOptions& c, double v) {
             c.statistical_plus.requery_distance_m = v;
             if (v > 0.0) c.statistical_plus.requery_parallax = 0.0;
         }},
        {{"without", "statistical+ with one improvement off: 0 none, 1 ready answers, 2 virtual leaves, 3 cost model, 4 re-query by distance, 5 fallback, 6 object queries (the ablation)"},
         0, 6, true, isStatisticalPlus, [](CullerOptions& c, double v) {
             StatisticalOptions& o = c.statistical_plus;
             switch (static_cast<int>(v)) {
                 case 1: o.ready_answers = false; break;
                 case 2: o.virtual_leaves = false; break;
                 case 3: o.cost_model = false; break;
                 case 4: o.requery_distance_m = o.requery_parallax = 0.0; break;
                 case 5: o.fallback = false; break;
                 case 6: o.object_queries = false; break;
                 default: break;
             }
         }},
        {{"retest", "frames; how often the per-object async scheme re-tests a visible object"},
         1, 1000, true, isAsync,
         [](CullerOptions& c, double v) { c.async.retest_interval_frames = static_cast<uint32_t>(v); }},
    };
    return all;
}

const Knob& knobNamed(const std::string& name) {
    for (const Knob& k : knobs()) {
        if (name == k.parameter.name) return k;
    }
    std::string names;
    for (const Knob& k : knobs()) names += (names.empty() ? "" : ", ") + std::string(k.parameter.name);
    throw std::invalid_argument("unknown sweep parameter '" + name + "'; expected one of: " + names);
}

std::string formatValue(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

}  // namespace

const std::vector<SweepParameter>& sweepParameters() {
    static const std::vector<SweepParameter> list = [] {
        std::vector<SweepParameter> out;
        for (const Knob& k : knobs()) out.push_back(k.parameter);
        return out;
    }();
    return list;
}

Sweep parseSweep(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
        throw std::invalid_argument("expected NAME=V1,V2,..., got '" + text + "'");
    }
    Sweep sweep;
    sweep.parameter = text.substr(0, eq);
    const Knob& knob = knobNamed(sweep.parameter);
    size_t start = eq + 1;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, comma - start);
        size_t used = 0;
        double v = 0;
        try {
            v = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (item.empty() || used != item.size() || !std::isfinite(v)) {
            throw std::invalid_argument(sweep.parameter + ": expected a number, got '" + item + "'");
        }
        if (v < knob.min || v > knob.max || (knob.integer && v != std::floor(v))) {
            throw std::invalid_argument(sweep.parameter + ": expected " +
                                        (knob.integer ? "an integer" : "a number") + " in [" +
                                        formatValue(knob.min) + ", " + formatValue(knob.max) +
                                        "], got " + item);
        }
        sweep.values.push_back(v);
        start = comma + 1;
    }
    return sweep;
}

std::vector<RunConfig> planConfigs(const std::vector<const AlgorithmTraits*>& algorithms,
                                   const CullerOptions& base, const std::optional<Sweep>& sweep) {
    std::vector<RunConfig> configs;
    const Knob* knob = sweep ? &knobNamed(sweep->parameter) : nullptr;
    for (const AlgorithmTraits* algorithm : algorithms) {
        const RunConfig plain{std::string(algorithm->name), algorithm, base};
        if (!knob || !knob->applies(*algorithm)) {
            configs.push_back(plain);
            continue;
        }
        for (double v : sweep->values) {
            RunConfig c = plain;
            c.label = plain.label + " " + sweep->parameter + "=" + formatValue(v);
            knob->set(c.culler, v);
            std::string why;
            if (!c.culler.isValid(&why)) {
                throw std::invalid_argument(sweep->parameter + "=" + formatValue(v) + ": " + why);
            }
            configs.push_back(c);
        }
    }
    return configs;
}

}  // namespace occsim
