// The choice: an optimum beyond the range ends on its bound and says so, integers chosen as run.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tune/choice.h"
#include "tune/report.h"
#include "tune_fixtures.h"

namespace occsim::tune {
namespace {

using namespace fixtures;

// One parameter's response in unit coordinates, falling towards 1.8: beyond the box's upper end.
std::vector<double> bowlBeyondTheUpperEnd(const std::vector<Point>& xs) {
    std::vector<double> ys;
    for (const Point& x : xs) ys.push_back(1.0 + 0.2 * (x[0] - 1.8) * (x[0] - 1.8));
    return ys;
}

// An optimum beyond the searched range ends on its bound, and the console and report say so with
// the --bounds that widens the range.
TEST(Choice, AnOptimumBeyondTheRangeEndsOnItsBoundAndIsReportedWithTheWiderRange) {
    TuneResult r;
    r.space = parseParameterSpace(statistical(), "base_time", {"base_time=0.2:0.6"});
    const std::vector<Point> xs = latinHypercube(8, 1, 3);
    r.response = selectResponseModel(xs, bowlBeyondTheUpperEnd(xs), 1, 200, &r.dropped);
    chooseTunedValues(r, r.space);
    ASSERT_FALSE(r.kept_at_paper[0]) << "the samples show the effect";
    EXPECT_DOUBLE_EQ(r.tuned_values[0], 0.6);
    EXPECT_EQ(r.bounds_hit[0], "upper");
    const std::vector<std::string> lines = boundWarnings(r);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("base_time = 0.6 s sits on the upper bound of its search range [0.2, "
                            "0.6]: the best value may lie beyond it; widen it, e.g. --bounds "
                            "base_time=0.2:1"),
              std::string::npos)
        << lines[0];
}

// An integer option's optimum is reported as the integer the confirmation runs (apply() rounds),
// within its bounds: confirmation.json once said queries_before_restart=22.71 for a run of 23.
TEST(Choice, AnIntegerOptionIsChosenAsTheIntegerTheConfirmationRuns) {
    const CullerRow& plus = *findCuller("statistical+");
    for (const auto& [bounds, expected] : std::vector<std::pair<std::string, double>>{
             {"queries_before_restart=1:32", 19.0}, {"queries_before_restart=1:18.6", 18.0}}) {
        TuneResult r;
        r.space = parseParameterSpace(plus, "queries_before_restart", {bounds});
        // A bowl whose minimum lies at 19.3 in the option's own unit (beyond 18.6 in the second
        // box, where the optimum is its upper bound, 18.6, and 18 the integer within it).
        const std::vector<Point> xs = latinHypercube(10, 1, 3);
        std::vector<double> ys;
        const double opt = r.space.unit(0, 19.3);
        for (const Point& x : xs) ys.push_back(1.0 + 0.3 * (x[0] - opt) * (x[0] - opt));
        r.response = selectResponseModel(xs, ys, 1, 200, &r.dropped);
        chooseTunedValues(r, r.space);
        ASSERT_FALSE(r.kept_at_paper[0]) << bounds;
        EXPECT_EQ(r.tuned_values[0], expected) << bounds;
        EXPECT_EQ(r.space.apply(OptionValues(plus.options), r.tuned_values)
                      .number("queries_before_restart"),
                  expected)
            << bounds;
        EXPECT_NEAR(r.space.value(0, r.tuned_unit[0]), expected, 1e-9)
            << "the prediction is at the value run";
        EXPECT_EQ(r.bounds_hit[0], expected == 18.0 ? "upper" : "") << bounds;
    }
}

// A parameter the samples show no effect of stays at its reference value, even where --bounds
// excluded it: a result outside the searched range, said in one line.
TEST(Choice, AValueKeptOutsideTheSearchedRangeIsSaidWithWhy) {
    TuneResult r;
    r.space = parseParameterSpace(statistical(), "base_time", {"base_time=0.05:0.1"});
    const std::vector<Point> xs = latinHypercube(12, 1, 5);
    Rng rng(9);
    std::vector<double> ys;
    for (size_t i = 0; i < xs.size(); ++i) ys.push_back(1.0 + 0.02 * gaussian(rng));
    r.response = selectResponseModel(xs, ys, 1, 200, &r.dropped);
    chooseTunedValues(r, r.space);
    ASSERT_TRUE(r.kept_at_paper[0]) << "pure noise: no effect";
    EXPECT_NEAR(r.tuned_values[0], 2.0 / 3.0, 1e-12);
    const std::vector<std::string> lines = boundWarnings(r);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("base_time = 0.6667 s (the paper's values) lies outside its search "
                            "range [0.05, 0.1]: kept there because the samples showed no effect "
                            "of it beyond noise"),
              std::string::npos)
        << lines[0];
}

}  // namespace
}  // namespace occsim::tune
