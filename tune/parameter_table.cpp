#include "tune/parameter_table.h"

#include <sstream>

#include "occsim/culling/registry/registry.h"
#include "tune/parameters.h"
#include "tune/response_model.h"

namespace occsim::tune {
namespace {

std::string range(const OptionSpec& spec, double lo, double hi) {
    return formatOptionValue(spec, lo) + " to " + formatOptionValue(spec, hi);
}

}  // namespace

std::string tunableParametersMarkdown() {
    std::ostringstream out;
    out << "| culler | parameter | unit | default (the reference) | search range (`--bounds` "
           "default) | valid range | what |\n"
        << "|---|---|---|---|---|---|---|\n";
    std::ostringstream budgets;
    for (const CullerRow* a : cullerRows()) {
        size_t count = 0;
        for (const OptionSpec& s : a->options) {
            if (!s.tunable) continue;
            ++count;
            out << "| `" << a->name << "` | `" << s.key << "` | " << (s.unit.empty() ? "–" : s.unit)
                << " | `" << formatOptionValue(s, s.default_value) << "` | "
                << range(s, s.tune_min, s.tune_max) << " | " << range(s, s.min, s.max) << " | "
                << s.doc << " |\n";
        }
        if (count == 0) continue;
        budgets << (budgets.tellp() > 0 ? ", " : "") << "`" << a->name << "` " << count << " ("
                << minimumSamples(count) << ")";
    }
    out << "\nTunable parameters per culler (the smallest `--budget` that tunes them all): "
        << budgets.str() << ".\n";
    return out.str();
}

std::string tunableParametersText() {
    std::ostringstream out;
    for (const CullerRow* a : cullerRows()) {
        for (const OptionSpec& s : a->options) {
            if (!s.tunable) continue;
            out << a->name << " " << s.key << ": default " << formatOptionValue(s, s.default_value)
                << (s.unit.empty() ? "" : " " + s.unit) << ", searched "
                << range(s, s.tune_min, s.tune_max) << ", valid " << range(s, s.min, s.max) << ": "
                << s.doc << "\n";
        }
    }
    return out.str();
}

}  // namespace occsim::tune
