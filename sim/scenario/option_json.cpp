#include "sim/scenario/option_json.h"

#include <cstdint>

namespace occsim {

nlohmann::ordered_json optionValuesJson(const OptionValues& values) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    const OptionsDescriptor& descriptor = values.descriptor();
    for (size_t i = 0; i < descriptor.size(); ++i) {
        const OptionSpec& spec = descriptor[i];
        const double v = values.values()[i];
        if (spec.type == OptionType::Boolean) {
            out[spec.key] = v != 0.0;
        } else if (spec.type == OptionType::Integer) {
            // Signed: an integer option's range may reach below 0 (options.h: within +-2^53).
            out[spec.key] = static_cast<int64_t>(v);
        } else {
            out[spec.key] = v;
        }
    }
    return out;
}

double readOptionValue(const JsonValueReader& value, const OptionSpec& spec) {
    if (spec.type == OptionType::Boolean) return value.asBool() ? 1.0 : 0.0;
    if (!value.json().is_number()) value.failExpected(describeOptionRange(spec));
    const double v = value.json().get<double>();
    if (const std::string why = checkOptionValue(spec, v); !why.empty()) value.fail(why);
    return v;
}

}  // namespace occsim
