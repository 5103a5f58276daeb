// The sampling design: a reproducible Latin hypercube, and batches around the optimum.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "tune/result.h"
#include "tune_fixtures.h"

namespace occsim::tune {
namespace {

using namespace fixtures;

TEST(Design, LatinHypercubeHasOnePointPerStratumAndIsReproducible) {
    const auto a = latinHypercube(9, 3, 77);
    ASSERT_EQ(a.size(), 9u);
    for (size_t j = 0; j < 3; ++j) {
        std::set<int> strata;
        for (const Point& p : a) {
            ASSERT_GE(p[j], 0.0);
            ASSERT_LT(p[j], 1.0);
            strata.insert(static_cast<int>(p[j] * 9));
        }
        EXPECT_EQ(strata.size(), 9u) << "axis " << j;
    }
    EXPECT_EQ(a, latinHypercube(9, 3, 77));
    EXPECT_NE(a, latinHypercube(9, 3, 78));
}

TEST(Design, NextBatchStartsAtTheOptimumAndKeepsItsDistance) {
    const Data d = responseData(14, 0.01, 61, trueResponse);
    ResponseFit fit = fitResponse(d.xs, d.ys, 3, {0, 1, 2});
    const Point optimum = minimiseOverBox(fit.model, {0.5, 0.5, 0.5});
    const std::vector<Point> batch = nextBatch(fit, d.xs, optimum, 4, 9, 2.0, 0.05);
    ASSERT_EQ(batch.size(), 4u);
    EXPECT_EQ(batch[0], optimum);
    for (size_t i = 0; i < batch.size(); ++i) {
        for (const Point& p : d.xs) EXPECT_GE(distance(batch[i], p), 0.05);
        for (size_t k = 0; k < i; ++k) EXPECT_GE(distance(batch[i], batch[k]), 0.05);
    }
}

}  // namespace
}  // namespace occsim::tune
