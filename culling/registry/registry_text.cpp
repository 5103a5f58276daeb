#include "occsim/culling/registry/registry_text.h"

#include <cmath>
#include <sstream>

#include "occsim/culling/registry/registry.h"

namespace occsim {
namespace {

std::string traitsOf(const CullerRow& a) {
    std::string t = a.conservative ? "conservative" : "not conservative";
    if (a.issues_queries) t += ", issues queries";
    if (a.oracle) t += ", oracle";
    if (a.speedup_reference) t += ", speedup reference";
    if (a.device_needs != 0) t += ", needs " + deviceFeatureNames(a.device_needs);
    if (!a.source.empty()) t += ", plugin " + a.source;
    return t;
}

std::string rangeOf(const OptionSpec& s) {
    if (s.type == OptionType::Boolean) return "true / false";
    const std::string lo = formatOptionValue(s, s.min);
    const std::string hi = std::isinf(s.max) ? "" : formatOptionValue(s, s.max);
    return hi.empty() ? ">= " + lo : "[" + lo + ", " + hi + "]";
}

std::string tuningOf(const OptionSpec& s) {
    std::string t;
    if (s.tunable)
        t = "tunable " + formatOptionValue(s, s.tune_min) + " to " +
            formatOptionValue(s, s.tune_max);
    if (s.off_value)
        t += std::string(t.empty() ? "" : "; ") + "off: " + formatOptionValue(s, *s.off_value);
    return t;
}

}  // namespace

std::string cullersText() {
    std::ostringstream out;
    for (const CullerRow* a : cullerRows()) {
        out << a->name << ": " << a->summary << " (" << traitsOf(*a) << ")\n";
        for (const OptionSpec& s : a->options) {
            out << "  " << s.key << " = " << formatOptionValue(s, s.default_value) << "  "
                << optionTypeName(s.type) << " " << rangeOf(s)
                << (s.unit.empty() ? "" : " " + s.unit);
            if (const std::string t = tuningOf(s); !t.empty()) out << " (" << t << ")";
            out << ": " << s.doc << "\n";
        }
    }
    return out.str();
}

std::string cullersMarkdown() {
    std::ostringstream out;
    out << "| `algorithm` | what | conservative | issues queries | oracle | options |\n"
        << "|---|---|---|---|---|---|\n";
    for (const CullerRow* a : cullerRows()) {
        out << "| `" << a->name << "` | " << a->summary << " | "
            << (a->conservative ? "yes" : "**no**") << " | " << (a->issues_queries ? "yes" : "no")
            << " | " << (a->oracle ? "yes" : "no") << " | "
            << (a->options.empty() ? std::string("–") : "`culling[\"" + a->name + "\"]`") << " |\n";
    }
    for (const CullerRow* a : cullerRows()) {
        if (a->options.empty()) continue;
        out << "\n### `" << a->name << "`\n\n"
            << "| Key | Type | Unit | Default | Valid values | Tuning, ablation | What |\n"
            << "|---|---|---|---|---|---|---|\n";
        for (const OptionSpec& s : a->options) {
            const std::string t = tuningOf(s);
            out << "| `" << s.key << "` | " << optionTypeName(s.type) << " | "
                << (s.unit.empty() ? "–" : s.unit) << " | `"
                << formatOptionValue(s, s.default_value) << "` | " << rangeOf(s) << " | "
                << (t.empty() ? "–" : t) << " | " << s.doc << " |\n";
        }
    }
    return out.str();
}

}  // namespace occsim
