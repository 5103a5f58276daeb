#include "tune/design.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "occsim/culling/geometry/random.h"

namespace occsim::tune {
namespace {

constexpr uint32_t kCandidatesPerDimension = 400;

double closestPair(const std::vector<Point>& points) {
    double closest = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < points.size(); ++i) {
        for (size_t j = i + 1; j < points.size(); ++j)
            closest = std::min(closest, distance(points[i], points[j]));
    }
    return closest;
}

double closestTo(const Point& x, const std::vector<Point>& a, const std::vector<Point>& b) {
    double closest = std::numeric_limits<double>::infinity();
    for (const Point& p : a) closest = std::min(closest, distance(x, p));
    for (const Point& p : b) closest = std::min(closest, distance(x, p));
    return closest;
}

}  // namespace

double distance(const Point& a, const Point& b) {
    double sum = 0.0;
    for (size_t j = 0; j < a.size(); ++j) sum += (a[j] - b[j]) * (a[j] - b[j]);
    return std::sqrt(sum);
}

std::vector<Point> latinHypercube(size_t n, size_t d, uint64_t seed, uint32_t tries) {
    Rng rng(seed);
    std::vector<Point> best;
    double best_spread = -1.0;
    for (uint32_t t = 0; t < std::max(1u, tries); ++t) {
        std::vector<Point> points(n, Point(d));
        std::vector<uint32_t> strata(n);
        for (size_t j = 0; j < d; ++j) {
            std::iota(strata.begin(), strata.end(), 0u);
            for (size_t i = n; i > 1; --i)
                std::swap(strata[i - 1], strata[rng.below(static_cast<uint32_t>(i))]);
            for (size_t i = 0; i < n; ++i)
                points[i][j] = (strata[i] + rng.uniform()) / static_cast<double>(n);
        }
        const double spread = n > 1 ? closestPair(points) : 0.0;
        if (spread > best_spread) {
            best_spread = spread;
            best = std::move(points);
        }
    }
    return best;
}

std::vector<Point> nextBatch(Surrogate& model, const std::vector<Point>& sampled,
                             const Point& optimum, size_t k, uint64_t seed, double kappa,
                             double min_distance) {
    std::vector<Point> chosen;
    if (k == 0) return chosen;
    const size_t d = optimum.size();
    if (closestTo(optimum, sampled, chosen) >= min_distance) {
        chosen.push_back(optimum);
        model.assumeSampled(optimum);
    }

    Rng rng(seed);
    std::vector<Point> candidates(kCandidatesPerDimension * std::max<size_t>(1, d), Point(d));
    for (Point& c : candidates) {
        for (double& v : c) v = rng.uniform();
    }
    while (chosen.size() < k) {
        double best_score = std::numeric_limits<double>::infinity();
        const Point* best = nullptr;
        for (const Point& c : candidates) {
            if (closestTo(c, sampled, chosen) < min_distance) continue;
            const Prediction p = model.predict(c);
            const double score = p.mean - kappa * p.stddev;
            if (score < best_score) {
                best_score = score;
                best = &c;
            }
        }
        if (!best) break;  // the candidates are all taken: a smaller batch
        chosen.push_back(*best);
        model.assumeSampled(*best);
    }
    return chosen;
}

}  // namespace occsim::tune
