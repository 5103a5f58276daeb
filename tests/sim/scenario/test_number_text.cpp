// Numbers read from text: the whole text or nothing, no infinities.
#include <gtest/gtest.h>

#include "sim/scenario/number_text.h"

namespace occsim {
namespace {

// The one parser of numbers typed as text (--sweep, --params, view scripts) keeps what each of
// the three copies it replaced took: stod's syntax for doubles, from_chars' for integers.
TEST(NumberText, FiniteNumbersUseTheWholeTextAndRefuseInfinities) {
    double v = 0;
    EXPECT_TRUE(parseFiniteNumber("1.5", v));
    EXPECT_EQ(v, 1.5);
    EXPECT_TRUE(parseFiniteNumber("-2e3", v));
    EXPECT_EQ(v, -2000.0);
    EXPECT_TRUE(parseFiniteNumber(" 4", v)) << "stod skips leading spaces, as the flags did";
    EXPECT_EQ(v, 4.0);
    for (const char* bad : {"", "x", "1.5x", "4 ", "inf", "nan", "1e999", "true"}) {
        EXPECT_FALSE(parseFiniteNumber(bad, v)) << "'" << bad << "'";
    }
}

TEST(NumberText, IntegersUseTheWholeTextWithoutSpacesOrPlus) {
    int64_t v = 0;
    EXPECT_TRUE(parseInteger("42", v));
    EXPECT_EQ(v, 42);
    EXPECT_TRUE(parseInteger("-7", v));
    EXPECT_EQ(v, -7);
    for (const char* bad : {"", "+1", " 1", "1 ", "1.0", "0x10", "99999999999999999999"}) {
        EXPECT_FALSE(parseInteger(bad, v)) << "'" << bad << "'";
    }
}

}  // namespace
}  // namespace occsim
