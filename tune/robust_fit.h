// Robust, bounded linear least squares through Ceres: the one solver both of the tuner's models
// are fitted with. Minimises sum_i huber(x_i . beta - y_i) over beta within per-coefficient bounds.
// The Huber loss counts a residual beyond `huber_delta` linearly instead of squared, so a frame or
// a sample that another process on a shared machine slowed down pulls the fit less.
#pragma once

#include <Eigen/Dense>

#include <string>
#include <vector>

namespace occsim::tune {

struct RobustFitOptions {
    double huber_delta = 1.0;          // in the unit of y
    std::vector<double> lower, upper;  // per coefficient; empty = unbounded
    int max_iterations = 200;          // Ceres' max_num_iterations
};

struct RobustFit {
    Eigen::VectorXd coefficients;
    bool converged = false;
    std::string ceres_summary;  // Ceres' own one-line summary (Solver::Summary::BriefReport())
    double residual_rms = 0.0;  // of the plain residuals, in the unit of y
    int iterations = 0;
};

// X: one row per observation, one column per coefficient; rows >= columns. The solver starts
// from zero (clamped into the bounds), so an iteration limit that is too small shows as a fit
// that did not converge.
RobustFit fitRobustLinear(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const RobustFitOptions& options);

}  // namespace occsim::tune
