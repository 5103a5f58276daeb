#include "occsim/culling/declaration/options.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace occsim {
namespace {

std::string number(double v) {
    char buf[40];
    // Integral values print as integers, without exponent, up to 2^53.
    if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) <= kMaxExactInteger) {
        std::snprintf(buf, sizeof buf, "%.0f", v);
    } else {
        std::snprintf(buf, sizeof buf, "%.10g", v);
    }
    return buf;
}

bool validKey(const std::string& key) {
    if (key.empty()) return false;
    for (char c : key) {
        const bool ok =
            (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '+';
        if (!ok) return false;
    }
    return true;
}

OptionSpec make(std::string key, OptionType type, std::string unit, double min, double max,
                double default_value, std::string doc) {
    OptionSpec s;
    s.key = std::move(key);
    s.type = type;
    s.unit = std::move(unit);
    s.min = min;
    s.max = max;
    s.default_value = default_value;
    s.doc = std::move(doc);
    return s;
}

}  // namespace

OptionSpec booleanOption(std::string key, bool default_value, std::string doc) {
    return make(std::move(key), OptionType::Boolean, "", 0.0, 1.0, default_value ? 1.0 : 0.0,
                std::move(doc));
}

OptionSpec integerOption(std::string key, std::string unit, double min, double max,
                         double default_value, std::string doc) {
    return make(std::move(key), OptionType::Integer, std::move(unit), min, max, default_value,
                std::move(doc));
}

OptionSpec numberOption(std::string key, std::string unit, double min, double max,
                        double default_value, std::string doc) {
    return make(std::move(key), OptionType::Number, std::move(unit), min, max, default_value,
                std::move(doc));
}

OptionSpec tunable(OptionSpec spec, double lo, double hi) {
    spec.tunable = true;
    spec.tune_min = lo;
    spec.tune_max = hi;
    return spec;
}

OptionSpec switchable(OptionSpec spec, double off_value) {
    spec.off_value = off_value;
    return spec;
}

OptionSpec alternativeTo(OptionSpec spec, std::string other_key) {
    spec.alternative_to = std::move(other_key);
    return spec;
}

OptionSpec actingOn(OptionSpec spec, OptionScope scope) {
    spec.scope = scope;
    return spec;
}

const char* optionTypeName(OptionType type) {
    switch (type) {
        case OptionType::Boolean:
            return "boolean";
        case OptionType::Integer:
            return "integer";
        case OptionType::Number:
            return "number";
    }
    return "number";
}

std::string describeOptionRange(const OptionSpec& spec) {
    if (spec.type == OptionType::Boolean) return "true or false";
    std::string text = spec.type == OptionType::Integer ? "an integer" : "a number";
    if (std::isinf(spec.max)) {
        text += " >= " + number(spec.min);
    } else {
        text += " in [" + number(spec.min) + ", " + number(spec.max) + "]";
    }
    if (!spec.unit.empty()) text += " (" + spec.unit + ")";
    return text;
}

std::string checkOptionValue(const OptionSpec& spec, double value) {
    const bool integral = value == std::floor(value);
    bool ok = std::isfinite(value) && value >= spec.min && value <= spec.max;
    if (spec.type != OptionType::Number) ok = ok && integral;
    if (ok) return {};
    return "expected " + describeOptionRange(spec) + ", got " + number(value);
}

std::string checkDescriptor(const OptionsDescriptor& descriptor) {
    for (size_t i = 0; i < descriptor.size(); ++i) {
        const OptionSpec& s = descriptor[i];
        const std::string where = "option " + std::to_string(i) + " ('" + s.key + "')";
        if (!validKey(s.key)) return where + ": the key must be non-empty, made of a-z 0-9 _ + -";
        for (size_t j = 0; j < i; ++j) {
            if (descriptor[j].key == s.key) return where + ": the key is declared twice";
        }
        if (s.doc.empty()) return where + ": no documentation line";
        if (std::isnan(s.min) || std::isnan(s.max) || !(s.min <= s.max)) {
            return where + ": the range must be ordered (min <= max)";
        }
        if (!std::isfinite(s.min)) return where + ": the lower end of the range must be finite";
        if (s.type == OptionType::Boolean && (s.min != 0.0 || s.max != 1.0)) {
            return where + ": a boolean's range is [0, 1]";
        }
        if (s.type == OptionType::Integer &&
            (s.min != std::floor(s.min) || s.min < -kMaxExactInteger || s.max > kMaxExactInteger ||
             (std::isfinite(s.max) && s.max != std::floor(s.max)))) {
            return where + ": an integer's range must have integral ends within [-2^53, 2^53]";
        }
        if (const std::string why = checkOptionValue(s, s.default_value); !why.empty()) {
            return where + ": the default is outside its range: " + why;
        }
        if (s.tunable) {
            if (s.type == OptionType::Boolean) return where + ": a boolean cannot be tuned";
            if (!(std::isfinite(s.tune_min) && std::isfinite(s.tune_max) &&
                  s.tune_min < s.tune_max && s.tune_min >= s.min && s.tune_max <= s.max)) {
                return where + ": the tuning bounds must be finite, lo < hi, inside the range";
            }
        }
        if (s.off_value) {
            if (const std::string why = checkOptionValue(s, *s.off_value); !why.empty()) {
                return where + ": the off value is outside its range: " + why;
            }
        }
        if (!s.alternative_to.empty()) {
            bool found = false;
            for (const OptionSpec& other : descriptor) {
                found |= other.key == s.alternative_to && other.key != s.key && other.off_value;
            }
            if (!found) {
                return where +
                       ": alternative_to must name another option of this culler that has an "
                       "off value";
            }
        }
    }
    return {};
}

OptionValues::OptionValues(const OptionsDescriptor& descriptor) : descriptor_(&descriptor) {
    values_.reserve(descriptor.size());
    for (const OptionSpec& s : descriptor) values_.push_back(s.default_value);
}

const OptionsDescriptor& OptionValues::descriptor() const {
    static const OptionsDescriptor kNone;
    return descriptor_ ? *descriptor_ : kNone;
}

const OptionSpec* OptionValues::find(std::string_view key) const {
    for (const OptionSpec& s : descriptor()) {
        if (s.key == key) return &s;
    }
    return nullptr;
}

size_t OptionValues::indexOf(std::string_view key) const {
    const OptionsDescriptor& d = descriptor();
    for (size_t i = 0; i < d.size(); ++i) {
        if (d[i].key == key) return i;
    }
    throw std::logic_error("no culler option '" + std::string(key) + "' in this descriptor");
}

double OptionValues::number(std::string_view key) const { return values_[indexOf(key)]; }

void OptionValues::set(std::string_view key, double value) { values_[indexOf(key)] = value; }

void OptionValues::setWithAlternatives(std::string_view key, double value) {
    const size_t i = indexOf(key);
    values_[i] = value;
    const OptionSpec& s = descriptor()[i];
    if (s.alternative_to.empty()) return;
    if (s.off_value && value == *s.off_value) return;
    const size_t other = indexOf(s.alternative_to);
    values_[other] = *descriptor()[other].off_value;
}

std::string formatOptionValue(const OptionSpec& spec, double value) {
    if (spec.type == OptionType::Boolean) return value != 0.0 ? "true" : "false";
    return number(value);
}

}  // namespace occsim
