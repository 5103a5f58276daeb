// What the tuner may tune: the statistical culler's BASE_TIME and decay curve (Kovalčík & Sochor,
// "Occlusion Culling with Statistically Optimized Occlusion Queries", WSCG 2005, section 3:
// re-query after last_query_time + BASE_TIME * (2 - 0.5^occ_num)), named as in a scenario's
// "culling.statistical" object, and the box of values a run searches.
#pragma once

#include "culling/culler_options.h"

#include <string>
#include <vector>

namespace occsim::tune {

struct TunableParameter {
    const char* name;         // key in culling.statistical, and in --params / --bounds
    const char* unit;         // for tables and charts ("s", or "" for a plain number)
    double paper_value;       // the paper's choice, the reference every sample is measured against
    double default_lo, default_hi;  // the search box when --bounds does not say
    double StatisticalOptions::*field;
};

// base_time, decay_a, decay_b.
const std::vector<TunableParameter>& tunableParameters();
std::string tunableParameterNames();  // "base_time, decay_a, decay_b"

struct Bounds {
    double lo = 0.0, hi = 1.0;
};

// The tuned parameters and their search box. Samples live in the unit cube [0, 1]^d; value()
// maps a coordinate to the parameter's own unit.
struct ParameterSpace {
    std::vector<const TunableParameter*> parameters;
    std::vector<Bounds> bounds;

    size_t size() const { return parameters.size(); }
    double value(size_t j, double unit) const;
    double unit(size_t j, double value) const;
    std::vector<double> values(const std::vector<double>& unit_point) const;
    std::vector<double> unitPoint(const std::vector<double>& values) const;
    // The paper's values, in the unit cube (may lie outside it when --bounds excludes them).
    std::vector<double> paperUnitPoint() const;
    // `base` with the tuned fields set to `values`; the others untouched.
    StatisticalOptions apply(StatisticalOptions base, const std::vector<double>& values) const;
    // `base` with the tuned fields at the paper's values.
    StatisticalOptions paper(StatisticalOptions base) const;
    // "base_time=0.667 decay_a=2" for labels and logs.
    std::string describe(const std::vector<double>& values) const;
};

// --params "base_time,decay_a" and --bounds "base_time=0.1:2" ... Throws TuneInputError with one
// line: an unknown or repeated parameter, a malformed, empty or inverted range, a range for a
// parameter that is not tuned, or a range whose ends make the culler's options invalid
// (StatisticalOptions::isValid).
ParameterSpace parseParameterSpace(const std::string& params, const std::vector<std::string>& bounds);

}  // namespace occsim::tune
