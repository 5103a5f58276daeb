#include "tune/robust_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace occsim::tune {
namespace {

// r = x . beta - y with its exact Jacobian x: the model is linear, so no automatic
// differentiation is needed.
class LinearResidual final : public ceres::CostFunction {
  public:
    LinearResidual(Eigen::VectorXd row, double y) : row_(std::move(row)), y_(y) {
        set_num_residuals(1);
        mutable_parameter_block_sizes()->push_back(static_cast<int>(row_.size()));
    }

    bool Evaluate(double const* const* parameters, double* residuals,
                  double** jacobians) const override {
        const Eigen::Map<const Eigen::VectorXd> beta(parameters[0], row_.size());
        residuals[0] = row_.dot(beta) - y_;
        if (jacobians != nullptr && jacobians[0] != nullptr) {
            for (Eigen::Index i = 0; i < row_.size(); ++i) jacobians[0][i] = row_[i];
        }
        return true;
    }

  private:
    Eigen::VectorXd row_;
    double y_;
};

enum class Loss { Huber, Cauchy };

// One Ceres solve from `start`; the problem owns the cost functions and losses it is given.
ceres::Solver::Summary solve(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                             const RobustFitOptions& options, Loss loss, double scale,
                             Eigen::VectorXd& beta) {
    ceres::Problem problem;
    double* b = beta.data();
    for (Eigen::Index r = 0; r < X.rows(); ++r) {
        ceres::LossFunction* rho =
            loss == Loss::Huber ? static_cast<ceres::LossFunction*>(new ceres::HuberLoss(scale))
                                : new ceres::CauchyLoss(scale);
        problem.AddResidualBlock(new LinearResidual(X.row(r).transpose(), y[r]), rho, b);
    }
    for (Eigen::Index i = 0; i < beta.size(); ++i) {
        const size_t k = static_cast<size_t>(i);
        if (k < options.lower.size())
            problem.SetParameterLowerBound(b, static_cast<int>(i), options.lower[k]);
        if (k < options.upper.size())
            problem.SetParameterUpperBound(b, static_cast<int>(i), options.upper[k]);
    }
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = options.max_iterations;
    solver.logging_type = ceres::SILENT;
    solver.minimizer_progress_to_stdout = false;
    solver.num_threads = 1;  // small problems; the machine's cores render
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    return summary;
}

double robustSpread(const Eigen::VectorXd& residuals) {
    std::vector<double> a(residuals.size());
    for (Eigen::Index i = 0; i < residuals.size(); ++i)
        a[static_cast<size_t>(i)] = std::abs(residuals[i]);
    if (a.empty()) return 0.0;
    std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(a.size() / 2), a.end());
    return 1.4826 * a[a.size() / 2];  // the standard deviation, for normal residuals
}

std::string threeDigits(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

}  // namespace

RobustFit fitRobustLinear(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                          const RobustFitOptions& options) {
    RobustFit fit;
    fit.coefficients = Eigen::VectorXd::Zero(X.cols());
    for (Eigen::Index i = 0; i < X.cols(); ++i) {
        const size_t k = static_cast<size_t>(i);
        if (k < options.lower.size())
            fit.coefficients[i] = std::max(fit.coefficients[i], options.lower[k]);
        if (k < options.upper.size())
            fit.coefficients[i] = std::min(fit.coefficients[i], options.upper[k]);
    }

    ceres::Solver::Summary summary =
        solve(X, y, options, Loss::Huber, options.huber_delta, fit.coefficients);
    fit.converged = summary.termination_type == ceres::CONVERGENCE;
    fit.iterations = static_cast<int>(summary.iterations.size());
    fit.loss = "Huber " + threeDigits(options.huber_delta);
    if (fit.converged && options.cauchy_refinement) {
        const double scale =
            std::max(options.cauchy_min_scale,
                     options.cauchy_spread_factor * robustSpread(X * fit.coefficients - y));
        summary = solve(X, y, options, Loss::Cauchy, scale, fit.coefficients);
        fit.converged = summary.termination_type == ceres::CONVERGENCE;
        fit.iterations += static_cast<int>(summary.iterations.size());
        fit.loss += " then Cauchy " + threeDigits(scale);
    }
    fit.ceres_summary = summary.BriefReport();
    const Eigen::VectorXd residuals = X * fit.coefficients - y;
    fit.residual_rms =
        X.rows() > 0 ? std::sqrt(residuals.squaredNorm() / static_cast<double>(X.rows())) : 0.0;
    return fit;
}

}  // namespace occsim::tune
