#include "sim/run/run_config.h"

#include <algorithm>
#include <stdexcept>

#include "sim/scenario/number_text.h"

namespace occsim {
namespace {

// A sweep value: a finite number, or true/false for a switch.
bool parseNumber(const std::string& item, double& v) {
    if (item == "true") return v = 1.0, true;
    if (item == "false") return v = 0.0, true;
    return parseFiniteNumber(item, v);
}

const OptionSpec* sharedOption(const std::string& key) {
    for (const OptionSpec& s : sharedQueryOptions()) {
        if (s.key == key) return &s;
    }
    return nullptr;
}

// The row of `key` for `algorithm`: its own option, or a shared query knob when it issues queries.
const OptionSpec* specFor(const CullerRow& algorithm, const std::string& key) {
    for (const OptionSpec& s : algorithm.options) {
        if (s.key == key) return &s;
    }
    if (algorithm.issues_queries) return sharedOption(key);
    return nullptr;
}

bool applies(const Sweep& sweep, const CullerRow& algorithm) {
    if (!sweep.algorithm.empty() && sweep.algorithm != algorithm.name) return false;
    return specFor(algorithm, sweep.parameter) != nullptr;
}

void setValue(CullerOptions& options, const CullerRow& algorithm, const std::string& key,
              double v) {
    if (key == "threshold_pixels") {
        options.approximation.threshold_pixels = static_cast<uint32_t>(v);
    } else if (key == "stale_results") {
        options.approximation.stale_results = v != 0.0;
    } else {
        options.edit(algorithm).setWithAlternatives(key, v);
    }
}

// The same culler with the same resolved values (a boolean given as true or as 1 alike) and the
// same shared knobs: two such configurations would measure one thing under two rows.
bool sameConfiguration(const RunConfig& a, const RunConfig& b) {
    if (a.algorithm != b.algorithm) return false;
    const ApproximationOptions& x = a.culler.approximation;
    const ApproximationOptions& y = b.culler.approximation;
    return a.culler.of(*a.algorithm) == b.culler.of(*b.algorithm) &&
           x.threshold_pixels == y.threshold_pixels && x.stale_results == y.stale_results;
}

void refuseRepeats(const std::vector<RunConfig>& configs) {
    for (size_t j = 0; j < configs.size(); ++j) {
        for (size_t i = 0; i < j; ++i) {
            if (!sameConfiguration(configs[i], configs[j])) continue;
            throw std::invalid_argument(
                "'" + configs[j].label + "' would run the same options as '" + configs[i].label +
                "' (a swept value the ablation also switches off?); expected each configuration "
                "once");
        }
    }
}

}  // namespace

const std::vector<OptionSpec>& sharedQueryOptions() {
    static const std::vector<OptionSpec> options = {
        integerOption("threshold_pixels", "pixels", 0, 4294967295.0, 0,
                      "a query passing at most this many samples counts as occluded (approximate)"),
        booleanOption("stale_results", false,
                      "results not ready when needed are taken from the previous frame instead of "
                      "waited for (approximate)"),
    };
    return options;
}

Sweep parseSweep(const std::string& text, const std::vector<const CullerRow*>& algorithms) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
        throw std::invalid_argument("expected [ALGORITHM:]KEY=V1,V2,..., got '" + text + "'");
    }
    Sweep sweep;
    std::string name = text.substr(0, eq);
    if (const auto colon = name.find(':'); colon != std::string::npos) {
        sweep.algorithm = name.substr(0, colon);
        name = name.substr(colon + 1);
        bool listed = false;
        for (const CullerRow* a : algorithms) listed |= a->name == sweep.algorithm;
        if (!listed) {
            throw std::invalid_argument("'" + sweep.algorithm +
                                        "' is not among the algorithms run (--algos)");
        }
    }
    sweep.parameter = name;
    // Every algorithm it applies to reads the same row: a key means one thing wherever it is.
    const OptionSpec* spec = nullptr;
    for (const CullerRow* a : algorithms) {
        if (applies(sweep, *a)) spec = specFor(*a, name);
    }
    if (!spec) {
        std::string keys;
        for (const CullerRow* a : algorithms) {
            if (!sweep.algorithm.empty() && a->name != sweep.algorithm) continue;
            for (const OptionSpec& s : a->options) {
                if (keys.find(" " + s.key + ",") == std::string::npos) keys += " " + s.key + ",";
            }
        }
        keys = " threshold_pixels, stale_results," + keys;
        keys.pop_back();
        throw std::invalid_argument("'" + name + "' is an option of none of the algorithms run; " +
                                    "expected one of:" + keys);
    }
    size_t start = eq + 1;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, comma - start);
        double v = 0;
        if (item.empty() || !parseNumber(item, v)) {
            throw std::invalid_argument(name + ": expected a value, got '" + item + "'");
        }
        if (const std::string why = checkOptionValue(*spec, v); !why.empty()) {
            throw std::invalid_argument(name + ": " + why);
        }
        // Two equal values (1,1 or true,1) would be two configurations under one label.
        if (std::find(sweep.values.begin(), sweep.values.end(), v) != sweep.values.end()) {
            throw std::invalid_argument(name + ": " + formatOptionValue(*spec, v) +
                                        " is listed twice (as '" + item +
                                        "' too); expected each value once");
        }
        sweep.values.push_back(v);
        start = comma + 1;
    }
    return sweep;
}

std::vector<RunConfig> planConfigs(const std::vector<const CullerRow*>& algorithms,
                                   const CullerOptions& base, const std::optional<Sweep>& sweep,
                                   const std::string& ablate) {
    std::vector<RunConfig> configs;
    bool ablated = ablate.empty();
    for (const CullerRow* algorithm : algorithms) {
        const RunConfig plain{algorithm->name, algorithm, base};
        if (!sweep || !applies(*sweep, *algorithm)) {
            configs.push_back(plain);
        } else {
            const OptionSpec& spec = *specFor(*algorithm, sweep->parameter);
            for (double v : sweep->values) {
                RunConfig c = plain;
                c.label = plain.label + " " + sweep->parameter + "=" + formatOptionValue(spec, v);
                setValue(c.culler, *algorithm, sweep->parameter, v);
                std::string why;
                if (!c.culler.isValid(&why)) {
                    throw std::invalid_argument(sweep->parameter + "=" +
                                                formatOptionValue(spec, v) + ": " + why);
                }
                configs.push_back(c);
            }
        }
        if (algorithm->name != ablate) continue;
        // The ablation: each mechanism the configuration has on, switched off on its own.
        ablated = true;
        const OptionValues values = base.of(*algorithm);
        size_t rows = 0;
        for (const OptionSpec& spec : algorithm->options) {
            if (!spec.off_value || values.number(spec.key) == *spec.off_value) continue;
            RunConfig c = plain;
            c.label = plain.label + " " + spec.key + "=" + formatOptionValue(spec, *spec.off_value);
            c.culler.edit(*algorithm).set(spec.key, *spec.off_value);
            configs.push_back(c);
            ++rows;
        }
        if (rows == 0) {
            throw std::invalid_argument("'" + ablate +
                                        "' has no mechanism switched on to switch off (its "
                                        "descriptor gives no option an off value, or all are off)");
        }
    }
    if (!ablated) throw std::invalid_argument("'" + ablate + "' is not among the algorithms run");
    refuseRepeats(configs);
    return configs;
}

}  // namespace occsim
