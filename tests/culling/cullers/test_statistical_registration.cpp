// The statistical cullers' registration (culling/cullers/statistical_registration.cpp): each row of
// their option table reads back into their options struct.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "culling/cullers/statistical_culler.h"
#include "occsim/culling/declaration/option_table.h"
#include "occsim/culling/registry/registry.h"

namespace occsim {
namespace {

// A value in range other than `spec`'s default (and other than `avoid`, when the range allows).
double otherValue(const OptionSpec& spec, double avoid) {
    if (spec.type == OptionType::Boolean) return spec.default_value != 0.0 ? 0.0 : 1.0;
    for (double candidate : {spec.min, spec.min + 1.0, spec.min + 2.0, spec.min + 0.5}) {
        if (candidate <= spec.max && candidate != spec.default_value && candidate != avoid &&
            checkOptionValue(spec, candidate).empty()) {
            return candidate;
        }
    }
    return spec.default_value;
}

// Every row sets the member it reads: two rows bound to one member, or a setter that loses the
// value, read back differently.
TEST(OptionTable, EveryStatisticalRowReadsBackTheValueItWasGiven) {
    const OptionTable<StatisticalOptions>& table = statisticalOptionTable();
    const OptionsDescriptor d = table.descriptor(StatisticalOptions::paper());
    OptionValues values(d);
    double previous = std::numeric_limits<double>::quiet_NaN();
    for (const OptionSpec& spec : d) {
        previous = otherValue(spec, previous);
        values.set(spec.key, previous);
    }
    const StatisticalOptions o = table.read(values);
    for (const OptionRow<StatisticalOptions>& row : table.rows()) {
        EXPECT_EQ(row.get(o), values.number(row.spec.key)) << row.spec.key;
    }
}

// A member that statistical+ changes but no row sets would read back as the paper's value.
TEST(OptionTable, BothStatisticalCullersReadTheirDefaultsBackAsTheirStructs) {
    EXPECT_EQ(statisticalOptionTable().read(OptionValues(findCuller("statistical")->options)),
              StatisticalOptions::paper());
    EXPECT_EQ(statisticalOptionTable().read(OptionValues(findCuller("statistical+")->options)),
              StatisticalOptions::plus());
}

}  // namespace
}  // namespace occsim
