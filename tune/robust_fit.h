// Robust, bounded linear least squares through Ceres: the one solver both of the tuner's models
// are fitted with. Minimises sum_i loss(x_i . beta - y_i) over beta within per-coefficient bounds,
// in two stages:
//   1. Huber loss (convex, so the start does not matter): a residual beyond `huber_delta` counts
//      linearly instead of squared;
//   2. from there, Cauchy loss with its scale set from stage 1's residuals (a multiple of their
//      robust spread, 1.4826 * median |r|): a residual far beyond the noise counts almost nothing.
// Frame times on a shared machine have one-sided outliers (another process took the CPU); the
// Huber loss alone still lets each of them pull the fit by up to its scale, the Cauchy loss
// does not.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace occsim::tune {

struct RobustFitOptions {
    double huber_delta = 1.0;  // in the unit of y
    bool cauchy_refinement = true;
    double cauchy_spread_factor =
        2.0;  // Cauchy scale = this * the robust spread of stage 1's residuals
    double cauchy_min_scale = 1e-3;  // in the unit of y: noise-free data still gets a usable scale
    std::vector<double> lower, upper;  // per coefficient; empty = unbounded
    int max_iterations = 200;          // Ceres' max_num_iterations, per stage
};

struct RobustFit {
    Eigen::VectorXd coefficients;
    bool converged = false;     // every stage ended in Ceres' CONVERGENCE
    std::string ceres_summary;  // Ceres' own one-line summary (Solver::Summary::BriefReport()) of
                                // the last stage run: the failing one when a stage failed
    std::string loss;           // e.g. "Huber 2 then Cauchy 0.8"
    double residual_rms = 0.0;  // of the plain residuals, in the unit of y
    int iterations = 0;         // over both stages
};

// X: one row per observation, one column per coefficient; rows >= columns. Stage 1 starts from
// zero (clamped into the bounds), so an iteration limit that is too small shows as a fit that
// did not converge.
RobustFit fitRobustLinear(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                          const RobustFitOptions& options);

}  // namespace occsim::tune
