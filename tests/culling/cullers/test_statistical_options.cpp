// The statistical cullers' options (culling/cullers/statistical_options.h) as the registry checks
// and reads them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "culling/cullers/statistical_culler.h"
#include "occsim/culling/registry/registry.h"

namespace occsim {
namespace {

TEST(StatisticalOptions, TheDescriptorRejectsOutOfRangeValuesWithAMessageNamingTheKey) {
    for (const char* name : {"statistical", "statistical+"}) {
        const CullerRow& a = *findCuller(name);
        EXPECT_EQ(checkOptionValues(a, OptionValues(a.options)), "") << name;
        const auto rejected = [&](const char* key, double value) {
            OptionValues v(a.options);
            v.set(key, value);
            return checkOptionValues(a, v);
        };
        EXPECT_EQ(rejected("decay_b", 1.5), "decay_b: expected a number in [0, 1], got 1.5");
        EXPECT_EQ(rejected("history_length", 0).rfind("history_length: ", 0), 0u);
        EXPECT_EQ(rejected("base_time", std::nan("")).rfind("base_time: ", 0), 0u);
        EXPECT_EQ(rejected("ready_answers", 2).rfind("ready_answers: expected true or false", 0),
                  0u);
    }
    // The rule tying two options together is the culler's own (its validate hook).
    const CullerRow& plus = *findCuller("statistical+");
    OptionValues both(plus.options);
    both.set("requery_distance", 3.0);
    EXPECT_NE(checkOptionValues(plus, both).find("alternatives"), std::string::npos);
    // A sweep or the tuner sets one alternative and switches the other off.
    both.setWithAlternatives("requery_distance", 3.0);
    EXPECT_EQ(both.number("requery_parallax"), 0.0);
    EXPECT_EQ(checkOptionValues(plus, both), "");
    // The values a culler reads are the descriptor's defaults: the paper's, or every improvement.
    EXPECT_EQ(
        statisticalOptionTable().read(OptionValues(findCuller("statistical")->options)).base_time_s,
        StatisticalOptions::paper().base_time_s);
    EXPECT_TRUE(statisticalOptionTable().read(OptionValues(plus.options)).fallback);
}

}  // namespace
}  // namespace occsim
