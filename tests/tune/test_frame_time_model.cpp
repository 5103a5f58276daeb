// The cost model fitted to frames generated from known costs plus noise (and a few outliers) gives
// those costs back within the stated tolerances, non-negative, and says when it did not converge.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tune_fixtures.h"

namespace occsim::tune {
namespace {

using namespace fixtures;

const FrameTimeModel kTrueCost{6.0, 0.03, 0.09, 0.012, 1.0};

std::vector<std::vector<FrameCounts>> syntheticFrames(const FrameTimeModel& truth, double noise_ms,
                                                      double outlier_share, uint64_t seed) {
    Rng rng(seed);
    std::vector<std::vector<FrameCounts>> runs(16);
    for (auto& run : runs) {
        for (int i = 0; i < 60; ++i) {
            FrameCounts f;
            f.queries = rng.uniform(0, 400);
            f.triangles = rng.uniform(1e5, 2e6);
            f.objects_drawn = rng.uniform(100, 3000);
            f.wait_ms = rng.uniform(0, 40);
            f.frame_ms = truth.predict(f) + noise_ms * gaussian(rng);
            // Another process took the machine for this frame.
            if (rng.uniform() < outlier_share) f.frame_ms += rng.uniform(50, 150);
            run.push_back(f);
        }
    }
    return runs;
}

TEST(FrameTimeModel, FitRecoversKnownCostsFromNoisyFramesWithOutliers) {
    // 960 frames, 2 ms of noise, 3 % of frames slowed by 50-150 ms. Tolerance: 10 % of each
    // coefficient (5 % would still pass on this seed; the outliers bias a plain least-squares
    // fit by far more, see the next test).
    const FrameTimeModelFit fit = fitFrameTimeModel(syntheticFrames(kTrueCost, 2.0, 0.03, 11));
    ASSERT_TRUE(fit.fit.converged) << fit.fit.ceres_summary;
    EXPECT_NEAR(fit.model.constant_ms, kTrueCost.constant_ms, 0.10 * kTrueCost.constant_ms);
    EXPECT_NEAR(fit.model.query_ms, kTrueCost.query_ms, 0.10 * kTrueCost.query_ms);
    EXPECT_NEAR(fit.model.kilotriangle_ms, kTrueCost.kilotriangle_ms,
                0.10 * kTrueCost.kilotriangle_ms);
    EXPECT_NEAR(fit.model.draw_call_ms, kTrueCost.draw_call_ms, 0.10 * kTrueCost.draw_call_ms);
    EXPECT_NEAR(fit.model.wait_factor, kTrueCost.wait_factor, 0.10 * kTrueCost.wait_factor);
    EXPECT_EQ(fit.frames, 960u);
    EXPECT_EQ(fit.groups, 16u);
    EXPECT_NEAR(fit.model.triangleMs(), kTrueCost.kilotriangle_ms / 1000.0,
                0.10 * kTrueCost.kilotriangle_ms / 1000.0);
    // The held-out error is the noise plus the outliers' share, far below the frames' spread.
    EXPECT_TRUE(std::isfinite(fit.heldout_rms_ms));
    EXPECT_LT(fit.heldout_rms_ms, 25.0);
}

TEST(FrameTimeModel, WithoutOutliersTheFitIsTight) {
    const FrameTimeModelFit fit = fitFrameTimeModel(syntheticFrames(kTrueCost, 1.0, 0.0, 12));
    ASSERT_TRUE(fit.fit.converged) << fit.fit.ceres_summary;
    EXPECT_NEAR(fit.model.query_ms, kTrueCost.query_ms, 0.03 * kTrueCost.query_ms);
    EXPECT_NEAR(fit.model.kilotriangle_ms, kTrueCost.kilotriangle_ms,
                0.03 * kTrueCost.kilotriangle_ms);
    EXPECT_NEAR(fit.model.draw_call_ms, kTrueCost.draw_call_ms, 0.03 * kTrueCost.draw_call_ms);
    // Residual and held-out error are the noise (1 ms) within 20 %.
    EXPECT_NEAR(fit.residual_rms_ms, 1.0, 0.2);
    EXPECT_NEAR(fit.heldout_rms_ms, 1.0, 0.2);
    // The stated uncertainty covers the truth.
    EXPECT_LT(std::abs(fit.model.query_ms - kTrueCost.query_ms), 4 * fit.standard_error[1]);
}

TEST(FrameTimeModel, CoefficientsStayNonNegative) {
    // Frames whose time falls as queries rise: the bound keeps the query cost at 0.
    std::vector<std::vector<FrameCounts>> runs(2);
    Rng rng(3);
    for (auto& run : runs) {
        for (int i = 0; i < 50; ++i) {
            FrameCounts f;
            f.queries = rng.uniform(0, 100);
            f.triangles = rng.uniform(1e5, 2e5);
            f.objects_drawn = rng.uniform(10, 20);
            f.frame_ms = 50.0 - 0.1 * f.queries;
            run.push_back(f);
        }
    }
    const FrameTimeModelFit fit = fitFrameTimeModel(runs);
    EXPECT_GE(fit.model.query_ms, 0.0);
    EXPECT_GE(fit.model.wait_factor, 0.0);
}

TEST(FrameTimeModel, AnIterationLimitTooSmallIsReportedAsNotConverged) {
    const FrameTimeModelFit fit = fitFrameTimeModel(syntheticFrames(kTrueCost, 1.0, 0.0, 13), 1);
    EXPECT_FALSE(fit.fit.converged);
    EXPECT_NE(fit.fit.ceres_summary.find("Ceres Solver Report"), std::string::npos)
        << fit.fit.ceres_summary;
    EXPECT_NE(fit.fit.ceres_summary.find("NO_CONVERGENCE"), std::string::npos)
        << fit.fit.ceres_summary;
}

}  // namespace
}  // namespace occsim::tune
