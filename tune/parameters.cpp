#include "tune/parameters.h"

#include "tune/errors.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace occsim::tune {
namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

const TunableParameter* find(const std::string& name) {
    for (const TunableParameter& p : tunableParameters()) {
        if (name == p.name) return &p;
    }
    return nullptr;
}

const TunableParameter& known(const std::string& flag, const std::string& name) {
    if (const TunableParameter* p = find(name)) return *p;
    throw TuneInputError(flag + ": unknown parameter '" + name + "'; expected one of: " +
                         tunableParameterNames());
}

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, separator)) parts.push_back(part);
    if (!text.empty() && text.back() == separator) parts.emplace_back();
    return parts;
}

bool parseDouble(const std::string& text, double& out) {
    if (text.empty()) return false;
    size_t used = 0;
    try {
        out = std::stod(text, &used);
    } catch (const std::exception&) {
        return false;
    }
    return used == text.size() && std::isfinite(out);
}

// The search box must hold only valid options. Each parameter's validity does not depend on the
// others (StatisticalOptions::isValid checks each on its own), so its two ends suffice.
void checkEndsValid(const std::string& flag, const TunableParameter& p, const Bounds& b) {
    for (double end : {b.lo, b.hi}) {
        StatisticalOptions o;
        o.*p.field = end;
        std::string why;
        if (!o.isValid(&why)) {
            throw TuneInputError(flag + ": " + p.name + "=" + number(end) + " is not a valid setting: " + why);
        }
    }
}

}  // namespace

const std::vector<TunableParameter>& tunableParameters() {
    // The paper's BASE_TIME is 2/3 s; the box reaches from re-querying every few frames to past
    // the statistics' "too old" age (2 s by default), where a longer wait changes nothing. The
    // decay curve a - b^occ_num must stay >= 0 (a >= 1, b in [0, 1]); a up to 4 lets a long
    // unoccluded history wait four BASE_TIMEs.
    static const std::vector<TunableParameter> kParameters = {
        {"base_time", "s", 2.0 / 3.0, 0.05, 2.0, &StatisticalOptions::base_time_s},
        {"decay_a", "", 2.0, 1.0, 4.0, &StatisticalOptions::decay_a},
        {"decay_b", "", 0.5, 0.0, 1.0, &StatisticalOptions::decay_b},
    };
    return kParameters;
}

std::string tunableParameterNames() {
    std::string names;
    for (const TunableParameter& p : tunableParameters()) names += (names.empty() ? "" : ", ") + std::string(p.name);
    return names;
}

double ParameterSpace::value(size_t j, double u) const { return bounds[j].lo + u * (bounds[j].hi - bounds[j].lo); }

double ParameterSpace::unit(size_t j, double v) const { return (v - bounds[j].lo) / (bounds[j].hi - bounds[j].lo); }

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
    for (const TunableParameter* p : parameters) paper_values.push_back(p->paper_value);
    return unitPoint(paper_values);
}

StatisticalOptions ParameterSpace::apply(StatisticalOptions base, const std::vector<double>& values) const {
    for (size_t j = 0; j < size(); ++j) base.*parameters[j]->field = values[j];
    return base;
}

StatisticalOptions ParameterSpace::paper(StatisticalOptions base) const {
    for (const TunableParameter* p : parameters) base.*p->field = p->paper_value;
    return base;
}

std::string ParameterSpace::describe(const std::vector<double>& values) const {
    std::string text;
    for (size_t j = 0; j < size(); ++j) {
        if (j) text += ' ';
        text += parameters[j]->name;
        text += '=';
        text += number(values[j]);
    }
    return text;
}

ParameterSpace parseParameterSpace(const std::string& params, const std::vector<std::string>& bounds) {
    ParameterSpace space;
    for (const std::string& name : split(params, ',')) {
        if (name.empty()) throw TuneInputError("--params: empty parameter name in '" + params + "'");
        const TunableParameter& p = known("--params", name);
        for (const TunableParameter* q : space.parameters) {
            if (q == &p) throw TuneInputError("--params: '" + name + "' is listed twice");
        }
        space.parameters.push_back(&p);
        space.bounds.push_back({p.default_lo, p.default_hi});
    }
    if (space.parameters.empty()) throw TuneInputError("--params: no parameter given; expected some of: " + tunableParameterNames());

    for (const std::string& text : bounds) {
        const std::string flag = "--bounds " + text;
        const size_t eq = text.find('=');
        const size_t colon = text.find(':', eq == std::string::npos ? 0 : eq);
        if (eq == std::string::npos || colon == std::string::npos) {
            throw TuneInputError(flag + ": expected name=lo:hi, e.g. base_time=0.1:2");
        }
        const std::string name = text.substr(0, eq);
        const TunableParameter& p = known(flag, name);
        size_t j = 0;
        while (j < space.size() && space.parameters[j] != &p) ++j;
        if (j == space.size()) {
            throw TuneInputError(flag + ": '" + name + "' is not tuned (--params " + params + ")");
        }
        Bounds b;
        if (!parseDouble(text.substr(eq + 1, colon - eq - 1), b.lo) || !parseDouble(text.substr(colon + 1), b.hi)) {
            throw TuneInputError(flag + ": expected two finite numbers lo:hi");
        }
        if (b.lo == b.hi) throw TuneInputError(flag + ": empty range (lo = hi); expected lo < hi");
        if (b.lo > b.hi) throw TuneInputError(flag + ": inverted range (lo > hi); expected lo < hi");
        checkEndsValid(flag, p, b);
        space.bounds[j] = b;
    }
    return space;
}

}  // namespace occsim::tune
