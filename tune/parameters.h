// What the tuner may tune: the options a culler's descriptor marks tunable (for `statistical`,
// Kovalčík & Sochor's BASE_TIME and decay curve, WSCG 2005, section 3: re-query after
// last_query_time + BASE_TIME * (2 - 0.5^occ_num)), named as in the culler's options object of a
// scenario, and the box of values a session searches.
#pragma once

#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"

namespace occsim::tune {

struct TunableParameter {
    std::string name;  // key in culling.<algorithm>, and in --params / --bounds
    std::string unit;  // for tables and charts ("s", or "" for a plain number)
    // The reference every sample is measured against: the culler's default (for `statistical`,
    // the paper's choice).
    double paper_value = 0.0;
    double default_lo = 0.0, default_hi = 1.0;     // the search box when --bounds does not say
    double min = 0.0, max = 0.0;                   // the option's valid range (its descriptor's)
    bool integer = false;                          // an integer option: values are rounded
    OptionScope scope = OptionScope::EveryObject;  // what it acts on (its descriptor's)
};

// The tunable options of `algorithm`, in descriptor order.
std::vector<TunableParameter> tunableParameters(const CullerRow& algorithm);
std::string tunableParameterNames(const CullerRow& algorithm);  // "base_time, decay_a, ..."

// What the reference values are called in reports and on the console: "the paper's values" for
// `statistical` (Kovalčík & Sochor's BASE_TIME and decay curve), "the defaults" (its descriptor's)
// for any other culler; referenceLabel() is the short form for table columns ("paper",
// "default").
std::string referenceName(const CullerRow& algorithm);
std::string referenceLabel(const CullerRow& algorithm);

struct Bounds {
    double lo = 0.0, hi = 1.0;
};

// The tuned parameters and their search box. Samples live in the unit cube [0, 1]^d; value()
// maps a coordinate to the parameter's own unit.
struct ParameterSpace {
    const CullerRow* algorithm = nullptr;
    std::vector<TunableParameter> parameters;
    std::vector<Bounds> bounds;

    size_t size() const { return parameters.size(); }
    double value(size_t j, double unit) const;
    double unit(size_t j, double value) const;
    std::vector<double> values(const std::vector<double>& unit_point) const;
    std::vector<double> unitPoint(const std::vector<double>& values) const;
    // The reference values, in the unit cube (may lie outside it when --bounds excludes them).
    std::vector<double> paperUnitPoint() const;
    // `base` with the tuned options set to `values` (integers rounded; an option's alternative
    // switched off, as a sweep does); the others untouched.
    OptionValues apply(OptionValues base, const std::vector<double>& values) const;
    // `base` with the tuned options at the reference values.
    OptionValues paper(OptionValues base) const;
    // "base_time=0.667 decay_a=2" for labels and logs.
    std::string describe(const std::vector<double>& values) const;
    // Per parameter, whether `values[j]` sits on an end of its search box (within 1% of the box):
    // "lower", "upper" or "".
    std::vector<std::string> boundsHit(const std::vector<double>& values) const;
    // Without parameter j (and its bounds): one the scene gives nothing to act on.
    void remove(size_t j);
};

// --params "base_time,decay_a" (empty: every tunable option of the algorithm) and --bounds
// "base_time=0.1:2" ... Throws TuneInputError with one line: an algorithm with nothing tunable,
// an unknown or repeated parameter, a malformed, empty or inverted range, a range for a parameter
// that is not tuned, or a range outside the option's valid range.
ParameterSpace parseParameterSpace(const CullerRow& algorithm, const std::string& params,
                                   const std::vector<std::string>& bounds);

}  // namespace occsim::tune
