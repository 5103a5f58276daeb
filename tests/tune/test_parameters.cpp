// The parameter flags: names and bounds checked with one line each, bounds hit reported with the
// flag that widens them.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tune/errors.h"
#include "tune/report.h"
#include "tune_fixtures.h"

namespace occsim::tune {
namespace {

using namespace fixtures;

std::string inputError(const std::string& params, const std::vector<std::string>& bounds,
                       const char* algorithm = "statistical") {
    try {
        parseParameterSpace(*findCuller(algorithm), params, bounds);
    } catch (const TuneInputError& e) {
        return e.what();
    }
    return "";
}

TEST(Parameters, BoundsAndNamesAreCheckedWithOneLineEach) {
    EXPECT_NE(inputError("speed", {})
                  .find("unknown parameter 'speed' of statistical; expected one of: base_time, "
                        "decay_a, decay_b"),
              std::string::npos);
    EXPECT_NE(inputError("base_time,base_time", {}).find("twice"), std::string::npos);
    EXPECT_NE(inputError("base_time", {"base_time=1:1"}).find("empty range"), std::string::npos);
    EXPECT_NE(inputError("base_time", {"base_time=2:1"}).find("inverted range"), std::string::npos);
    EXPECT_NE(inputError("base_time", {"decay_a=1:2"}).find("not tuned"), std::string::npos);
    EXPECT_NE(inputError("decay_b", {"decay_b=0:2"})
                  .find("decay_b=2 is not a valid setting: expected a value in [0, 1]"),
              std::string::npos);
    EXPECT_NE(inputError("base_time", {"base_time=0.1"}).find("expected name=lo:hi"),
              std::string::npos);
    EXPECT_NE(inputError("base_time", {"base_time=a:1"}).find("two finite numbers"),
              std::string::npos);
    EXPECT_NE(inputError("base_time,", {}).find("empty parameter name"), std::string::npos);
    EXPECT_NE(inputError("", {}, "vfc").find("marks no option tunable"), std::string::npos);
    for (const std::string& e :
         {inputError("speed", {}), inputError("base_time", {"base_time=2:1"})}) {
        EXPECT_EQ(e.find('\n'), std::string::npos);
    }

    // No --params: every option the descriptor marks tunable, in its order; statistical+ declares
    // its own (BASE_TIME is unused while it re-queries by parallax; the bound on queries in
    // flight, an integer, is rounded when applied).
    const ParameterSpace every = parseParameterSpace(statistical(), "", {});
    ASSERT_EQ(every.size(), 3u);
    EXPECT_EQ(every.parameters[0].name, "base_time");
    const ParameterSpace plus = parseParameterSpace(*findCuller("statistical+"), "", {});
    ASSERT_EQ(plus.size(), 3u);
    EXPECT_EQ(plus.parameters[0].name, "queries_before_restart");
    EXPECT_TRUE(plus.parameters[0].integer);
    EXPECT_EQ(plus.parameters[1].name, "requery_parallax");
    EXPECT_EQ(plus.parameters[2].name, "waits_per_frame");
    EXPECT_TRUE(plus.parameters[2].integer);
    EXPECT_EQ(plus.parameters[2].default_lo, 1.0) << "0 switches the growing bound off";
    const OptionValues applied =
        plus.apply(OptionValues(findCuller("statistical+")->options), {7.6, 0.01, 3.4});
    EXPECT_EQ(applied.number("queries_before_restart"), 8.0);
    EXPECT_EQ(applied.number("waits_per_frame"), 3.0);
    EXPECT_EQ(applied.number("requery_parallax"), 0.01);

    const ParameterSpace s =
        parseParameterSpace(statistical(), "decay_a,base_time", {"base_time=0.2:1.2"});
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(s.parameters[0].name, "decay_a");
    EXPECT_EQ(s.bounds[1].lo, 0.2);
    EXPECT_EQ(s.bounds[1].hi, 1.2);
    EXPECT_NEAR(s.value(1, 0.5), 0.7, 1e-12);
    const OptionValues o = s.apply(OptionValues(statistical().options), {3.0, 0.9});
    EXPECT_EQ(o.number("decay_a"), 3.0);
    EXPECT_EQ(o.number("base_time"), 0.9);
    EXPECT_EQ(o.number("decay_b"), 0.5);
    const OptionValues paper = s.paper(o);
    EXPECT_EQ(paper.number("base_time"), 2.0 / 3.0);
    EXPECT_EQ(paper.number("decay_a"), 2.0);
    // A value on an end of its box is reported, so that the report can suggest widening it.
    EXPECT_EQ(s.boundsHit({2.0, 0.2}), (std::vector<std::string>{"", "lower"}));
    EXPECT_EQ(s.boundsHit({4.0, 0.7}), (std::vector<std::string>{"upper", ""}));
}

// A chosen value on an end of its search box is said, with the --bounds that widens it (within
// the option's valid range), on the console and in the report.
TEST(Parameters, AChosenValueOnABoundIsReportedWithTheBoundsThatWidenIt) {
    TuneResult r;
    r.space = parseParameterSpace(statistical(), "base_time,decay_b", {});
    r.tuned_values = {0.05, 0.0};
    r.kept_at_paper = {false, false};
    r.bounds_hit = r.space.boundsHit(r.tuned_values);
    const std::vector<std::string> lines = boundWarnings(r);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_NE(
        lines[0].find("base_time = 0.05 s sits on the lower bound of its search range [0.05, 2]"),
        std::string::npos)
        << lines[0];
    EXPECT_NE(lines[0].find("widen it, e.g. --bounds base_time=0:2"), std::string::npos)
        << lines[0];
    EXPECT_NE(lines[1].find("(the end of the option's valid range)"), std::string::npos)
        << lines[1];
    r.tuned_values = {0.7, 0.5};
    r.bounds_hit = r.space.boundsHit(r.tuned_values);
    EXPECT_TRUE(boundWarnings(r).empty());
}

}  // namespace
}  // namespace occsim::tune
