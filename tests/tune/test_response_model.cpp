// The response model fitted to samples of a known bowl gives its minimum back, drops what has no
// effect, keeps nothing of pure noise, and knows where it is uncertain.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tune/result.h"
#include "tune_fixtures.h"

namespace occsim::tune {
namespace {

using namespace fixtures;

TEST(ResponseModel, FitRecoversAKnownQuadraticAndItsMinimum) {
    // 30 samples with 0.5 % noise and one sample slowed by 30 %. Tolerances: predictions within
    // 0.015 of the truth anywhere in the cube (three standard deviations of a prediction at its
    // corners, where 30 samples constrain a 10-term quadratic least), the minimum within 0.1 of
    // the true one in every coordinate (normalised), its value within 0.005.
    Data d = responseData(30, 0.005, 21, trueResponse);
    d.ys[7] += 0.3;
    const ResponseFit fit = fitResponse(d.xs, d.ys, 3, {0, 1, 2});
    ASSERT_TRUE(fit.fit.converged) << fit.fit.ceres_summary;
    Rng rng(5);
    for (int i = 0; i < 200; ++i) {
        const Point x = {rng.uniform(), rng.uniform(), rng.uniform()};
        EXPECT_NEAR(fit.model.predict(x), trueResponse(x), 0.015);
    }
    const Point best = minimiseOverBox(fit.model, {0.5, 0.5, 0.5});
    EXPECT_NEAR(best[0], 0.3, 0.1);
    EXPECT_NEAR(best[1], 0.7, 0.1);
    EXPECT_NEAR(best[2], 0.5, 0.1);
    EXPECT_NEAR(fit.model.predict(best), 0.9, 0.005);
    // The leave-one-out error reflects the noise (and the outlier's own error, 0.3 / sqrt(30)).
    EXPECT_LT(fit.loo_rms, 0.1);
}

double dependsOnFirstTwo(const Point& x) {
    return 1.0 + 0.3 * (x[0] - 0.6) * (x[0] - 0.6) - 0.08 * x[1];
}

TEST(ResponseModel, AParameterWithNoEffectIsDropped) {
    const Data d = responseData(24, 0.004, 31, dependsOnFirstTwo);
    std::vector<size_t> dropped;
    const ResponseFit fit = selectResponseModel(d.xs, d.ys, 3, 200, &dropped);
    EXPECT_EQ(dropped, std::vector<size_t>{2});
    EXPECT_EQ(fit.model.active, (std::vector<size_t>{0, 1}));
    const Point best = minimiseOverBox(fit.model, {0.5, 0.5, 0.25});
    EXPECT_NEAR(best[0], 0.6, 0.1);
    EXPECT_NEAR(best[1], 1.0, 1e-9);  // on the face: the response falls along x1
    EXPECT_EQ(best[2], 0.25);         // not active: where it was asked to stay
}

TEST(ResponseModel, PureNoiseKeepsNoParameter) {
    Rng rng(8);
    std::vector<Point> xs = latinHypercube(20, 2, 41);
    std::vector<double> ys;
    for (size_t i = 0; i < xs.size(); ++i) ys.push_back(1.0 + 0.02 * gaussian(rng));
    std::vector<size_t> dropped;
    const ResponseFit fit = selectResponseModel(xs, ys, 2, 200, &dropped);
    EXPECT_TRUE(fit.model.active.empty());
    EXPECT_EQ(dropped.size(), 2u);
}

TEST(ResponseModel, TooFewSamplesForTheTermsIsAnError) {
    const Data d = responseData(10, 0.0, 1, trueResponse);
    EXPECT_THROW(fitResponse(d.xs, d.ys, 3, {0, 1, 2}), std::invalid_argument);
    EXPECT_EQ(minimumSamples(3), 12u);
    EXPECT_EQ(minimumSamples(1), 5u);
}

TEST(ResponseModel, MinimumOverTheBoxIsExactOnFacesAndCorners) {
    ResponseModel m;
    m.dims = 2;
    m.active = {0, 1};
    // In z = 2x - 1: f = z0^2 + z1^2 - 3 z0 (unconstrained minimum at z0 = 1.5: outside).
    m.coefficients.resize(6);
    m.coefficients << 0.0, -3.0, 0.0, 1.0, 0.0, 1.0;
    Point best = minimiseOverBox(m, {0.5, 0.5});
    EXPECT_NEAR(best[0], 1.0, 1e-12);
    EXPECT_NEAR(best[1], 0.5, 1e-12);
    // A saddle f = z0^2 - z1^2: the minimum is on the edges z1 = +-1, at z0 = 0.
    m.coefficients << 0.0, 0.0, 0.0, 1.0, 0.0, -1.0;
    best = minimiseOverBox(m, {0.5, 0.5});
    EXPECT_NEAR(best[0], 0.5, 1e-12);
    EXPECT_TRUE(std::abs(best[1]) < 1e-12 || std::abs(best[1] - 1.0) < 1e-12);
}

TEST(ResponseModel, UncertaintyShrinksWhereAPointIsAssumedSampled) {
    const Data d = responseData(15, 0.01, 51, trueResponse);
    ResponseFit fit = fitResponse(d.xs, d.ys, 3, {0, 1, 2});
    const Point corner = {1.0, 1.0, 0.0};
    const double before = fit.predict(corner).stddev;
    fit.assumeSampled(corner);
    EXPECT_LT(fit.predict(corner).stddev, before);
}

}  // namespace
}  // namespace occsim::tune
