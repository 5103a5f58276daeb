#include "tune/robust_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

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

    bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
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

}  // namespace

RobustFit fitRobustLinear(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const RobustFitOptions& options) {
    const Eigen::Index n = X.cols();
    RobustFit fit;
    fit.coefficients = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const size_t k = static_cast<size_t>(i);
        if (k < options.lower.size()) fit.coefficients[i] = std::max(fit.coefficients[i], options.lower[k]);
        if (k < options.upper.size()) fit.coefficients[i] = std::min(fit.coefficients[i], options.upper[k]);
    }

    ceres::Problem problem;
    double* beta = fit.coefficients.data();
    for (Eigen::Index r = 0; r < X.rows(); ++r) {
        // The problem takes ownership of the cost function and the loss.
        problem.AddResidualBlock(new LinearResidual(X.row(r).transpose(), y[r]),
                                 new ceres::HuberLoss(options.huber_delta), beta);
    }
    for (Eigen::Index i = 0; i < n; ++i) {
        const size_t k = static_cast<size_t>(i);
        if (k < options.lower.size()) problem.SetParameterLowerBound(beta, static_cast<int>(i), options.lower[k]);
        if (k < options.upper.size()) problem.SetParameterUpperBound(beta, static_cast<int>(i), options.upper[k]);
    }

    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = options.max_iterations;
    solver.logging_type = ceres::SILENT;
    solver.minimizer_progress_to_stdout = false;
    solver.num_threads = 1;  // small problems; the machine's cores render
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);

    fit.converged = summary.termination_type == ceres::CONVERGENCE;
    fit.ceres_summary = summary.BriefReport();
    fit.iterations = static_cast<int>(summary.iterations.size());
    const Eigen::VectorXd residuals = X * fit.coefficients - y;
    fit.residual_rms = X.rows() > 0 ? std::sqrt(residuals.squaredNorm() / static_cast<double>(X.rows())) : 0.0;
    return fit;
}

}  // namespace occsim::tune
