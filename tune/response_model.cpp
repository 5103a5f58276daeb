#include "tune/response_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace occsim::tune {
namespace {

// Loose bounds on every coefficient (the ratio is near 1, each term at most 1 in size): they only
// keep a badly conditioned fit from running off.
constexpr double kCoefficientBound = 50.0;

RobustFit fitTerms(const Eigen::MatrixXd& T, const Eigen::VectorXd& y, int max_iterations) {
    RobustFitOptions o;
    o.huber_delta = kResponseHuberDelta;
    o.cauchy_min_scale = kResponseMinCauchyScale;
    o.lower.assign(static_cast<size_t>(T.cols()), -kCoefficientBound);
    o.upper.assign(static_cast<size_t>(T.cols()), kCoefficientBound);
    o.max_iterations = max_iterations;
    return fitRobustLinear(T, y, o);
}

Eigen::MatrixXd termMatrix(const ResponseModel& m, const std::vector<Point>& xs) {
    Eigen::MatrixXd T(static_cast<Eigen::Index>(xs.size()),
                      static_cast<Eigen::Index>(ResponseModel::termCount(m.active.size())));
    for (size_t i = 0; i < xs.size(); ++i)
        T.row(static_cast<Eigen::Index>(i)) = m.terms(xs[i]).transpose();
    return T;
}

struct LeaveOneOut {
    double rms = 0.0;
    double mse_se = 0.0;
};

LeaveOneOut leaveOneOut(const ResponseModel& shape, const std::vector<Point>& xs,
                        const std::vector<double>& ys, int max_iterations) {
    const Eigen::MatrixXd T = termMatrix(shape, xs);
    const Eigen::Index n = T.rows();
    std::vector<double> squared_errors;
    for (Eigen::Index out = 0; out < n; ++out) {
        Eigen::MatrixXd Ti(n - 1, T.cols());
        Eigen::VectorXd yi(n - 1);
        for (Eigen::Index r = 0, k = 0; r < n; ++r) {
            if (r == out) continue;
            Ti.row(k) = T.row(r);
            yi[k++] = ys[static_cast<size_t>(r)];
        }
        const RobustFit f = fitTerms(Ti, yi, max_iterations);
        const double e = T.row(out).dot(f.coefficients) - ys[static_cast<size_t>(out)];
        squared_errors.push_back(e * e);
    }
    double mean = 0.0;
    for (double e2 : squared_errors) mean += e2;
    mean /= static_cast<double>(n);
    double variance = 0.0;
    for (double e2 : squared_errors) variance += (e2 - mean) * (e2 - mean);
    variance /= std::max<double>(1.0, static_cast<double>(n - 1));
    return {std::sqrt(mean), std::sqrt(variance / static_cast<double>(n))};
}

// The quadratic in z over the active parameters: f(z) = c + g.z + z^T H z / 2.
struct Quadratic {
    double c = 0.0;
    Eigen::VectorXd g;
    Eigen::MatrixXd H;
};

Quadratic quadraticOf(const ResponseModel& m) {
    const size_t a = m.active.size();
    Quadratic q{m.coefficients[0], Eigen::VectorXd::Zero(static_cast<Eigen::Index>(a)),
                Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(a))};
    Eigen::Index k = 1;
    for (size_t i = 0; i < a; ++i) q.g[static_cast<Eigen::Index>(i)] = m.coefficients[k++];
    for (size_t i = 0; i < a; ++i) {
        for (size_t j = i; j < a; ++j) {
            const double b = m.coefficients[k++];
            const auto ii = static_cast<Eigen::Index>(i), jj = static_cast<Eigen::Index>(j);
            if (i == j) {
                q.H(ii, ii) = 2.0 * b;
            } else {
                q.H(ii, jj) = b;
                q.H(jj, ii) = b;
            }
        }
    }
    return q;
}

double valueAt(const Quadratic& q, const Eigen::VectorXd& z) {
    return q.c + q.g.dot(z) + 0.5 * z.dot(q.H * z);
}

}  // namespace

size_t ResponseModel::termCount(size_t a) { return 1 + a + a * (a + 1) / 2; }

size_t minimumSamples(size_t dims) { return ResponseModel::termCount(dims) + 2; }

Eigen::VectorXd ResponseModel::terms(const Point& x) const {
    const size_t a = active.size();
    Eigen::VectorXd t(static_cast<Eigen::Index>(termCount(a)));
    std::vector<double> z(a);
    for (size_t i = 0; i < a; ++i) z[i] = 2.0 * x[active[i]] - 1.0;
    Eigen::Index k = 0;
    t[k++] = 1.0;
    for (size_t i = 0; i < a; ++i) t[k++] = z[i];
    for (size_t i = 0; i < a; ++i) {
        for (size_t j = i; j < a; ++j) t[k++] = z[i] * z[j];
    }
    return t;
}

double ResponseModel::predict(const Point& x) const { return terms(x).dot(coefficients); }

Prediction ResponseFit::predict(const Point& x) const {
    const Eigen::VectorXd t = model.terms(x);
    return {t.dot(model.coefficients), sigma * std::sqrt(std::max(0.0, t.dot(inverse_normal * t)))};
}

void ResponseFit::assumeSampled(const Point& x) {
    // Sherman-Morrison: (A + t t^T)^-1 = A^-1 - A^-1 t t^T A^-1 / (1 + t^T A^-1 t).
    const Eigen::VectorXd t = model.terms(x);
    const Eigen::VectorXd u = inverse_normal * t;
    inverse_normal -= (u * u.transpose()) / (1.0 + t.dot(u));
}

ResponseFit fitResponse(const std::vector<Point>& xs, const std::vector<double>& ys, size_t dims,
                        const std::vector<size_t>& active, int max_iterations) {
    ResponseFit r;
    r.model.dims = dims;
    r.model.active = active;
    const size_t terms = ResponseModel::termCount(active.size());
    if (xs.size() <= terms) {
        throw std::invalid_argument("the response model needs more samples (" +
                                    std::to_string(xs.size()) + ") than terms (" +
                                    std::to_string(terms) + ")");
    }
    const Eigen::MatrixXd T = termMatrix(r.model, xs);
    const Eigen::VectorXd y =
        Eigen::Map<const Eigen::VectorXd>(ys.data(), static_cast<Eigen::Index>(ys.size()));
    r.fit = fitTerms(T, y, max_iterations);
    r.model.coefficients = r.fit.coefficients;
    r.samples = xs.size();
    r.residual_rms = r.fit.residual_rms;
    const double n = static_cast<double>(xs.size());
    r.sigma = r.residual_rms * std::sqrt(n / (n - static_cast<double>(terms)));
    r.inverse_normal = (T.transpose() * T).completeOrthogonalDecomposition().pseudoInverse();
    const LeaveOneOut loo = leaveOneOut(r.model, xs, ys, max_iterations);
    r.loo_rms = loo.rms;
    r.loo_mse_se = loo.mse_se;
    return r;
}

ResponseFit selectResponseModel(const std::vector<Point>& xs, const std::vector<double>& ys,
                                size_t dims, int max_iterations, std::vector<size_t>* dropped) {
    std::vector<size_t> active(dims);
    for (size_t j = 0; j < dims; ++j) active[j] = j;
    ResponseFit current = fitResponse(xs, ys, dims, active, max_iterations);
    // The lowest leave-one-out mean squared error seen on the path, and its standard error.
    double best_mse = current.loo_rms * current.loo_rms;
    double best_se = current.loo_mse_se;
    while (!current.model.active.empty()) {
        std::optional<ResponseFit> simplest;
        size_t removed = 0;
        for (size_t i = 0; i < current.model.active.size(); ++i) {
            std::vector<size_t> fewer = current.model.active;
            fewer.erase(fewer.begin() + static_cast<std::ptrdiff_t>(i));
            ResponseFit candidate = fitResponse(xs, ys, dims, fewer, max_iterations);
            if (!simplest || candidate.loo_rms < simplest->loo_rms) {
                removed = current.model.active[i];
                simplest = std::move(candidate);
            }
        }
        const double mse = simplest->loo_rms * simplest->loo_rms;
        if (mse > best_mse + best_se) break;
        if (mse < best_mse) {
            best_mse = mse;
            best_se = simplest->loo_mse_se;
        }
        if (dropped) dropped->push_back(removed);
        current = std::move(*simplest);
    }
    return current;
}

Point minimiseOverBox(const ResponseModel& model, const Point& inactive_at) {
    Point best_x = inactive_at;
    const size_t a = model.active.size();
    if (a == 0) return best_x;
    const Quadratic q = quadraticOf(model);
    double best = std::numeric_limits<double>::infinity();
    Eigen::VectorXd best_z = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(a));

    // Each active coordinate is free (0), at its lower end (1) or at its upper end (2).
    size_t faces = 1;
    for (size_t i = 0; i < a; ++i) faces *= 3;
    for (size_t face = 0; face < faces; ++face) {
        Eigen::VectorXd z = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(a));
        std::vector<Eigen::Index> free;
        size_t code = face;
        for (size_t i = 0; i < a; ++i, code /= 3) {
            const auto ii = static_cast<Eigen::Index>(i);
            if (code % 3 == 0)
                free.push_back(ii);
            else
                z[ii] = code % 3 == 1 ? -1.0 : 1.0;
        }
        if (!free.empty()) {
            // Stationary point of the face: H_FF z_F = -(g_F + H_F,fixed z_fixed).
            const auto f = static_cast<Eigen::Index>(free.size());
            Eigen::MatrixXd Hff(f, f);
            Eigen::VectorXd rhs(f);
            for (Eigen::Index r = 0; r < f; ++r) {
                rhs[r] = -q.g[free[static_cast<size_t>(r)]];
                for (Eigen::Index c = 0; c < static_cast<Eigen::Index>(a); ++c) {
                    if (std::find(free.begin(), free.end(), c) == free.end())
                        rhs[r] -= q.H(free[static_cast<size_t>(r)], c) * z[c];
                }
                for (Eigen::Index c = 0; c < f; ++c)
                    Hff(r, c) = q.H(free[static_cast<size_t>(r)], free[static_cast<size_t>(c)]);
            }
            const Eigen::FullPivLU<Eigen::MatrixXd> lu(Hff);
            if (!lu.isInvertible())
                continue;  // a singular face: its minimum lies on a smaller face
            const Eigen::VectorXd zf = lu.solve(rhs);
            bool inside = true;
            for (Eigen::Index r = 0; r < f; ++r) inside &= zf[r] >= -1.0 && zf[r] <= 1.0;
            if (!inside) continue;
            for (Eigen::Index r = 0; r < f; ++r) z[free[static_cast<size_t>(r)]] = zf[r];
        }
        const double v = valueAt(q, z);
        if (v < best) {
            best = v;
            best_z = z;
        }
    }
    for (size_t i = 0; i < a; ++i)
        best_x[model.active[i]] = 0.5 * (best_z[static_cast<Eigen::Index>(i)] + 1.0);
    return best_x;
}

}  // namespace occsim::tune
