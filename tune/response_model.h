// The response model: the tuning objective (a sample's mean or p95 frame time as a ratio to the
// paper's defaults in the same interleaved run) as a smooth function of the tuned parameters,
//
//   ratio(x) = b0 + sum_i b_i z_i + sum_{i <= j} b_ij z_i z_j,   z = 2x - 1 in [-1, 1]^d,
//
// a quadratic in the normalised parameters (a second-order response surface: Box & Wilson, "On
// the Experimental Attainment of Optimum Conditions", JRSS B 1951), fitted with Ceres under a
// Huber loss. Only the "active" parameters enter it: a parameter whose terms do not lower the
// leave-one-out prediction error is dropped (the scene does not exercise it beyond noise).
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <vector>

#include "tune/design.h"
#include "tune/robust_fit.h"

namespace occsim::tune {

struct ResponseModel {
    size_t dims = 0;             // every tuned parameter (the length of a point)
    std::vector<size_t> active;  // the parameters the model depends on, ascending
    Eigen::VectorXd coefficients;

    static size_t termCount(size_t active_count);
    Eigen::VectorXd terms(const Point& x) const;
    double predict(const Point& x) const;
};

struct ResponseFit final : Surrogate {
    ResponseModel model;
    RobustFit fit;
    size_t samples = 0;
    double residual_rms = 0.0;  // over the samples fitted
    double loo_rms = 0.0;       // leave-one-out prediction error (each sample predicted without it)
    double loo_mse_se = 0.0;    // standard error of the leave-one-out mean squared error
    double sigma = 0.0;         // residual standard deviation, corrected for the terms fitted
    Eigen::MatrixXd
        inverse_normal;  // (T^T T)^-1 over the sampled terms, for the prediction's spread

    Prediction predict(const Point& x) const override;
    void assumeSampled(const Point& x) override;
};

// Huber scale of the response fit: 2 % of the reference's frame time; the Cauchy stage's scale
// is set from the residuals, at least 0.5 %.
inline constexpr double kResponseHuberDelta = 0.02;
inline constexpr double kResponseMinCauchyScale = 0.005;

// Needs more samples than terms. Throws std::invalid_argument otherwise.
ResponseFit fitResponse(const std::vector<Point>& xs, const std::vector<double>& ys, size_t dims,
                        const std::vector<size_t>& active, int max_iterations = 200);

// Backward elimination on the leave-one-out error with the one-standard-error rule (Hastie,
// Tibshirani & Friedman, "The Elements of Statistical Learning", 2nd ed., section 7.10): starting
// from every parameter, drop the parameter whose removal gives the lowest error, as long as that
// error stays within one standard error of the lowest seen so far. A parameter survives only when
// the samples show its effect beyond their noise. `dropped` lists the parameters removed, in order.
ResponseFit selectResponseModel(const std::vector<Point>& xs, const std::vector<double>& ys,
                                size_t dims, int max_iterations, std::vector<size_t>* dropped);

// The point of the unit cube where the model is lowest. Inactive parameters take their value from
// `inactive_at`. Exact: a quadratic's minimum over a box lies at a stationary point of one of the
// box's faces (the box itself, its facets, ..., its corners), so every face is solved.
Point minimiseOverBox(const ResponseModel& model, const Point& inactive_at);

// The smallest budget the full model (every tuned parameter) can be fitted and checked with: two
// samples more than it has terms, so that the fit has residuals and leave-one-out has a fit.
size_t minimumSamples(size_t dims);

}  // namespace occsim::tune
