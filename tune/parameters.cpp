#include "tune/parameters.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "sim/scenario/number_text.h"
#include "tune/errors.h"

namespace occsim::tune {
namespace {

std::string sixDigits(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

const TunableParameter* find(const ParameterSpace& all, const std::string& name) {
    for (const TunableParameter& p : all.parameters) {
        if (name == p.name) return &p;
    }
    return nullptr;
}

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, separator)) parts.push_back(part);
    if (!text.empty() && text.back() == separator) parts.emplace_back();
    return parts;
}

// The search box must hold only valid values: inside the option's own range.
void checkEndsValid(const std::string& flag, const TunableParameter& p, const Bounds& b) {
    for (double end : {b.lo, b.hi}) {
        if (!(end >= p.min && end <= p.max)) {
            throw TuneInputError(flag + ": " + p.name + "=" + sixDigits(end) +
                                 " is not a valid setting: expected a value in [" +
                                 sixDigits(p.min) + ", " + sixDigits(p.max) + "]");
        }
    }
}

}  // namespace

std::vector<TunableParameter> tunableParameters(const CullerRow& algorithm) {
    std::vector<TunableParameter> out;
    for (const OptionSpec& spec : algorithm.options) {
        if (!spec.tunable) continue;
        out.push_back({spec.key, spec.unit, spec.default_value, spec.tune_min, spec.tune_max,
                       spec.min, spec.max, spec.type == OptionType::Integer, spec.scope});
    }
    return out;
}

std::string tunableParameterNames(const CullerRow& algorithm) {
    std::string names;
    for (const TunableParameter& p : tunableParameters(algorithm))
        names += (names.empty() ? "" : ", ") + p.name;
    return names;
}

std::string referenceName(const CullerRow& algorithm) {
    return algorithm.name == "statistical" ? "the paper's values" : "the defaults";
}

std::string referenceLabel(const CullerRow& algorithm) {
    return algorithm.name == "statistical" ? "paper" : "default";
}

double ParameterSpace::value(size_t j, double u) const {
    return bounds[j].lo + u * (bounds[j].hi - bounds[j].lo);
}

double ParameterSpace::unit(size_t j, double v) const {
    return (v - bounds[j].lo) / (bounds[j].hi - bounds[j].lo);
}

std::vector<double> ParameterSpace::values(const std::vector<double>& unit_point) const {
    std::vector<double> v(size());
    for (size_t j = 0; j < size(); ++j) v[j] = value(j, unit_point[j]);
    return v;
}

std::vector<double> ParameterSpace::unitPoint(const std::vector<double>& values) const {
    std::vector<double> u(size());
    for (size_t j = 0; j < size(); ++j) u[j] = unit(j, values[j]);
    return u;
}

std::vector<double> ParameterSpace::paperUnitPoint() const {
    std::vector<double> paper_values;
    for (const TunableParameter& p : parameters) paper_values.push_back(p.paper_value);
    return unitPoint(paper_values);
}

OptionValues ParameterSpace::apply(OptionValues base, const std::vector<double>& values) const {
    for (size_t j = 0; j < size(); ++j) {
        const double v = parameters[j].integer ? std::round(values[j]) : values[j];
        base.setWithAlternatives(parameters[j].name, v);
    }
    return base;
}

OptionValues ParameterSpace::paper(OptionValues base) const {
    for (const TunableParameter& p : parameters) base.set(p.name, p.paper_value);
    return base;
}

std::vector<std::string> ParameterSpace::boundsHit(const std::vector<double>& values) const {
    std::vector<std::string> hit(size());
    for (size_t j = 0; j < size(); ++j) {
        const double margin = 0.01 * (bounds[j].hi - bounds[j].lo);
        if (values[j] <= bounds[j].lo + margin) hit[j] = "lower";
        if (values[j] >= bounds[j].hi - margin) hit[j] = "upper";
    }
    return hit;
}

std::string ParameterSpace::describe(const std::vector<double>& values) const {
    std::string text;
    for (size_t j = 0; j < size(); ++j) {
        if (j) text += ' ';
        text += parameters[j].name;
        text += '=';
        text += sixDigits(values[j]);
    }
    return text;
}

void ParameterSpace::remove(size_t j) {
    parameters.erase(parameters.begin() + static_cast<std::ptrdiff_t>(j));
    bounds.erase(bounds.begin() + static_cast<std::ptrdiff_t>(j));
}

ParameterSpace parseParameterSpace(const CullerRow& algorithm, const std::string& params,
                                   const std::vector<std::string>& bounds) {
    ParameterSpace all;
    all.parameters = tunableParameters(algorithm);
    if (all.parameters.empty()) {
        throw TuneInputError("--algo " + algorithm.name +
                             ": its options descriptor marks no option tunable; nothing to tune");
    }
    const std::string names = tunableParameterNames(algorithm);
    auto known = [&](const std::string& flag, const std::string& name) -> const TunableParameter& {
        if (const TunableParameter* p = find(all, name)) return *p;
        throw TuneInputError(flag + ": unknown parameter '" + name + "' of " + algorithm.name +
                             "; expected one of: " + names);
    };
    ParameterSpace space;
    space.algorithm = &algorithm;
    const std::vector<std::string> listed =
        params.empty() ? [&] {
            std::vector<std::string> v;
            for (const TunableParameter& p : all.parameters) v.push_back(p.name);
            return v;
        }()
                       : split(params, ',');
    for (const std::string& name : listed) {
        if (name.empty())
            throw TuneInputError("--params: empty parameter name in '" + params + "'");
        const TunableParameter& p = known("--params", name);
        for (const TunableParameter& q : space.parameters) {
            if (q.name == p.name) throw TuneInputError("--params: '" + name + "' is listed twice");
        }
        space.parameters.push_back(p);
        space.bounds.push_back({p.default_lo, p.default_hi});
    }

    for (const std::string& text : bounds) {
        const std::string flag = "--bounds " + text;
        const size_t eq = text.find('=');
        const size_t colon = text.find(':', eq == std::string::npos ? 0 : eq);
        if (eq == std::string::npos || colon == std::string::npos) {
            throw TuneInputError(flag + ": expected name=lo:hi, e.g. " +
                                 all.parameters.front().name + "=" +
                                 sixDigits(all.parameters.front().default_lo) + ":" +
                                 sixDigits(all.parameters.front().default_hi));
        }
        const std::string name = text.substr(0, eq);
        const TunableParameter& p = known(flag, name);
        size_t j = 0;
        while (j < space.size() && space.parameters[j].name != p.name) ++j;
        if (j == space.size()) {
            throw TuneInputError(flag + ": '" + name + "' is not tuned (--params " + params + ")");
        }
        Bounds b;
        if (!parseFiniteNumber(text.substr(eq + 1, colon - eq - 1), b.lo) ||
            !parseFiniteNumber(text.substr(colon + 1), b.hi)) {
            throw TuneInputError(flag + ": expected two finite numbers lo:hi");
        }
        if (b.lo == b.hi) throw TuneInputError(flag + ": empty range (lo = hi); expected lo < hi");
        if (b.lo > b.hi)
            throw TuneInputError(flag + ": inverted range (lo > hi); expected lo < hi");
        checkEndsValid(flag, p, b);
        space.bounds[j] = b;
    }
    return space;
}

}  // namespace occsim::tune
