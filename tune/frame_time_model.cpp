#include "tune/frame_time_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace occsim::tune {
namespace {

constexpr size_t kFolds = 5;
// Huber stage: residuals beyond a tenth of the typical frame count linearly; the Cauchy stage
// then discounts frames far beyond the noise (robust_fit.h). A frame slowed by another process
// is an outlier, not a cost.
constexpr double kHuberShareOfMedianFrame = 0.1;

Eigen::RowVectorXd termsOf(const FrameCounts& f) {
    Eigen::RowVectorXd row(FrameTimeModel::kTerms);
    row << 1.0, f.queries, f.triangles / 1000.0, f.objects_drawn, f.wait_ms;
    return row;
}

FrameTimeModel modelOf(const Eigen::VectorXd& c) { return {c[0], c[1], c[2], c[3], c[4]}; }

struct Data {
    Eigen::MatrixXd X;
    Eigen::VectorXd y;
};

Data dataOf(const std::vector<std::vector<FrameCounts>>& groups, size_t skip_fold, size_t folds) {
    size_t rows = 0;
    for (size_t g = 0; g < groups.size(); ++g)
        rows += (g % folds == skip_fold) ? 0 : groups[g].size();
    Data d{Eigen::MatrixXd(static_cast<Eigen::Index>(rows), FrameTimeModel::kTerms),
           Eigen::VectorXd(static_cast<Eigen::Index>(rows))};
    Eigen::Index r = 0;
    for (size_t g = 0; g < groups.size(); ++g) {
        if (g % folds == skip_fold) continue;
        for (const FrameCounts& f : groups[g]) {
            d.X.row(r) = termsOf(f);
            d.y[r++] = f.frame_ms;
        }
    }
    return d;
}

RobustFit fit(const Data& d, double delta, int max_iterations) {
    RobustFitOptions o;
    o.huber_delta = delta;
    o.cauchy_min_scale = 0.1 * delta;
    o.lower.assign(FrameTimeModel::kTerms, 0.0);
    o.max_iterations = max_iterations;
    return fitRobustLinear(d.X, d.y, o);
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace

double FrameTimeModel::predict(const FrameCounts& f) const {
    return constant_ms + query_ms * f.queries + kilotriangle_ms * f.triangles / 1000.0 +
           draw_call_ms * f.objects_drawn + wait_factor * f.wait_ms;
}

FrameTimeModelFit fitFrameTimeModel(const std::vector<std::vector<FrameCounts>>& groups,
                                    int max_iterations) {
    constexpr size_t kNone = std::numeric_limits<size_t>::max();
    const Data all = dataOf(groups, kNone, 1);
    if (static_cast<size_t>(all.X.rows()) < FrameTimeModel::kTerms) {
        throw std::invalid_argument("the cost model needs at least 5 frames");
    }
    std::vector<double> times(all.y.data(), all.y.data() + all.y.size());
    FrameTimeModelFit result;
    result.frames = times.size();
    result.groups = groups.size();
    result.mean_frame_ms = all.y.mean();
    const double delta = std::max(1e-3, kHuberShareOfMedianFrame * median(times));

    result.fit = fit(all, delta, max_iterations);
    result.model = modelOf(result.fit.coefficients);
    result.residual_rms_ms = result.fit.residual_rms;

    // Coefficient uncertainty: s^2 (X^T X)^-1, with the pseudo-inverse when a count never varied.
    const double n = static_cast<double>(all.X.rows());
    const double dof = std::max(1.0, n - static_cast<double>(FrameTimeModel::kTerms));
    const double s2 = result.residual_rms_ms * result.residual_rms_ms * n / dof;
    const Eigen::MatrixXd normal = all.X.transpose() * all.X;
    const Eigen::MatrixXd inverse = normal.completeOrthogonalDecomposition().pseudoInverse();
    for (size_t i = 0; i < FrameTimeModel::kTerms; ++i) {
        const Eigen::Index k = static_cast<Eigen::Index>(i);
        result.standard_error[i] = std::sqrt(std::max(0.0, s2 * inverse(k, k)));
    }

    // Whole runs left out, so that a frame is never predicted from its neighbours in time.
    const size_t folds = std::min(kFolds, groups.size());
    if (folds < 2) {
        result.heldout_rms_ms = std::numeric_limits<double>::quiet_NaN();
        return result;
    }
    double squared = 0.0;
    size_t count = 0;
    for (size_t fold = 0; fold < folds; ++fold) {
        const Data train = dataOf(groups, fold, folds);
        if (static_cast<size_t>(train.X.rows()) < FrameTimeModel::kTerms) continue;
        const FrameTimeModel m = modelOf(fit(train, delta, max_iterations).coefficients);
        for (size_t g = fold; g < groups.size(); g += folds) {
            for (const FrameCounts& f : groups[g]) {
                const double e = m.predict(f) - f.frame_ms;
                squared += e * e;
                ++count;
            }
        }
    }
    result.heldout_rms_ms = count > 0 ? std::sqrt(squared / static_cast<double>(count))
                                      : std::numeric_limits<double>::quiet_NaN();
    return result;
}

}  // namespace occsim::tune
