// Option rows (occsim/culling/declaration/options.h): what a value must be, the check of one
// value, the check of a whole descriptor, and the values a culler holds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "occsim/culling/declaration/options.h"

namespace occsim {
namespace {

TEST(OptionRows, TheRangeIsDescribedWithItsTypeAndUnit) {
    EXPECT_EQ(describeOptionRange(booleanOption("on", false, "doc")), "true or false");
    EXPECT_EQ(describeOptionRange(integerOption("n", "frames", 1, 32, 8, "doc")),
              "an integer in [1, 32] (frames)");
    EXPECT_EQ(describeOptionRange(numberOption("t", "", 0.0, INFINITY, 1.0, "doc")),
              "a number >= 0");
}

TEST(OptionRows, AValueOutOfRangeNotIntegralOrNotFiniteIsRefusedWithWhatWasExpected) {
    const OptionSpec n = integerOption("n", "frames", 1, 32, 8, "doc");
    EXPECT_EQ(checkOptionValue(n, 8), "");
    EXPECT_EQ(checkOptionValue(n, 0), "expected an integer in [1, 32] (frames), got 0");
    EXPECT_EQ(checkOptionValue(n, 2.5), "expected an integer in [1, 32] (frames), got 2.5");
    const OptionSpec b = booleanOption("on", false, "doc");
    EXPECT_EQ(checkOptionValue(b, 1), "");
    EXPECT_EQ(checkOptionValue(b, 2), "expected true or false, got 2");
    EXPECT_NE(checkOptionValue(numberOption("t", "s", 0, 1, 0, "doc"), std::nan("")), "");
}

TEST(OptionRows, AnUnsoundDescriptorIsRefusedNamingTheRow) {
    EXPECT_EQ(checkDescriptor({integerOption("n", "", 1, 32, 8, "doc")}), "");
    EXPECT_EQ(checkDescriptor({integerOption("n", "", 1, 32, 8, "doc"),
                               integerOption("n", "", 1, 32, 8, "doc")}),
              "option 1 ('n'): the key is declared twice");
    EXPECT_EQ(checkDescriptor({integerOption("n", "", 1, 32, 8, "")}),
              "option 0 ('n'): no documentation line");
    EXPECT_EQ(checkDescriptor({integerOption("n", "", 32, 1, 8, "doc")}),
              "option 0 ('n'): the range must be ordered (min <= max)");
    EXPECT_EQ(checkDescriptor({integerOption("Bad Key", "", 1, 32, 8, "doc")}),
              "option 0 ('Bad Key'): the key must be non-empty, made of a-z 0-9 _ + -");
    EXPECT_NE(checkDescriptor({integerOption("n", "", 1, 32, 40, "doc")}).find("the default"),
              std::string::npos);
}

TEST(OptionValues, StartAtTheDefaultsAndRefuseAKeyTheyDoNotHave) {
    const OptionsDescriptor d = {integerOption("n", "", 1, 32, 8, "doc"),
                                 booleanOption("on", true, "doc")};
    OptionValues v(d);
    EXPECT_EQ(v.count("n"), 8u);
    EXPECT_TRUE(v.flag("on"));
    v.set("n", 3);
    EXPECT_EQ(v.number("n"), 3.0);
    EXPECT_EQ(v.find("none"), nullptr);
    EXPECT_THROW(v.number("none"), std::logic_error);
    EXPECT_EQ(formatOptionValue(d[1], 0.0), "false");
}

}  // namespace
}  // namespace occsim
