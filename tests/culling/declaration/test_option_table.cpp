// occsim/culling/declaration/option_table.h: options structs bound to their descriptors, row by
// row.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "culling/cullers/statistical_culler.h"
#include "occsim/culling/declaration/option_table.h"
#include "occsim/culling/registry/registry.h"

namespace occsim {
namespace {

struct ToyOptions {
    bool on = true;
    uint32_t count = 3;
    uint64_t seed = 7;
    double wait_s = 0.5;
};

OptionTable<ToyOptions> toyTable() {
    using O = ToyOptions;
    return {
        booleanOption(OCCSIM_OPTION_MEMBER(O, on), "switches it"),
        integerOption(OCCSIM_OPTION_MEMBER(O, count), "frames", 1, 10, "how many"),
        integerOption(OCCSIM_OPTION_MEMBER(O, seed), "", 0, kMaxExactInteger, "seeds it"),
        numberOption(OptionMember{&O::wait_s, "wait"}, "s", 0.0, 2.0, "how long"),
    };
}

TEST(OptionTable, TheDescriptorTakesKeysFromTheRowsAndDefaultsFromTheStruct) {
    ToyOptions defaults;
    defaults.count = 5;
    const OptionsDescriptor d = toyTable().descriptor(defaults);
    ASSERT_EQ(d.size(), 4u);
    EXPECT_EQ(d[0].key, "on");
    EXPECT_EQ(d[0].type, OptionType::Boolean);
    EXPECT_EQ(d[0].default_value, 1.0);
    EXPECT_EQ(d[1].key, "count");
    EXPECT_EQ(d[1].type, OptionType::Integer);
    EXPECT_EQ(d[1].default_value, 5.0);
    EXPECT_EQ(d[3].key, "wait");  // a key that differs from its member's name
    EXPECT_EQ(d[3].unit, "s");
    EXPECT_EQ(checkDescriptor(d), "");
}

TEST(OptionTable, ReadSetsEachMemberFromItsKey) {
    const OptionTable<ToyOptions> table = toyTable();
    const OptionsDescriptor d = table.descriptor(ToyOptions{});
    OptionValues values(d);
    values.set("on", 0.0);
    values.set("count", 9.0);
    values.set("seed", 4503599627370497.0);  // 2^52 + 1: integers cross exactly
    values.set("wait", 1.25);
    const ToyOptions o = table.read(values);
    EXPECT_FALSE(o.on);
    EXPECT_EQ(o.count, 9u);
    EXPECT_EQ(o.seed, 4503599627370497u);
    EXPECT_EQ(o.wait_s, 1.25);
}

TEST(OptionTable, AnIntegerRangeThatDoesNotFitItsMemberIsRefused) {
    using O = ToyOptions;
    EXPECT_THROW(integerOption(OCCSIM_OPTION_MEMBER(O, count), "", 0, kMaxExactInteger, "too wide"),
                 std::logic_error);
    EXPECT_THROW(integerOption(OCCSIM_OPTION_MEMBER(O, count), "", -1, 10, "below 0"),
                 std::logic_error);
}

}  // namespace
}  // namespace occsim
