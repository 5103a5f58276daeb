// Where to sample: a space-filling start, then points where the fitted response model is
// uncertain or promising. Points live in the unit cube [0, 1]^d (ParameterSpace maps them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace occsim::tune {

using Point = std::vector<double>;

// A Latin hypercube of n points in [0, 1]^d (McKay, Beckman & Conover, "A Comparison of Three
// Methods for Selecting Values of Input Variables in the Analysis of Output from a Computer
// Code", Technometrics 1979): each axis cut into n equal strata, one point per stratum, at a
// random place within it. Of `tries` seeded designs, the one whose closest pair of points is
// farthest apart (maximin) is kept. The same seed gives the same design on every machine.
std::vector<Point> latinHypercube(size_t n, size_t d, uint64_t seed, uint32_t tries = 32);

// What a fitted model says at a point: its prediction and that prediction's standard deviation.
struct Prediction {
    double mean = 0.0;
    double stddev = 0.0;
};

class Surrogate {
  public:
    virtual ~Surrogate() = default;
    virtual Prediction predict(const Point& x) const = 0;
    // Counts x as sampled before its value is known: the uncertainty of a linear model depends
    // only on where it was sampled, so a point chosen for this batch already shrinks it.
    virtual void assumeSampled(const Point& x) = 0;
};

// The next k points: the model's predicted optimum `optimum` first (exploitation), then points
// of a seeded random candidate set with the lowest confidence bound mean - kappa * stddev
// (Srinivas et al., "Gaussian Process Optimization in the Bandit Setting", ICML 2010, on a
// linear model here), so that a point is worth measuring when it may be good or when little is
// known about it. Each chosen point counts as sampled for the next choice (its stddev there
// shrinks), and no point comes closer than `min_distance` to a sampled or chosen one.
std::vector<Point> nextBatch(Surrogate& model, const std::vector<Point>& sampled,
                             const Point& optimum, size_t k, uint64_t seed, double kappa = 2.0,
                             double min_distance = 0.02);

double distance(const Point& a, const Point& b);

}  // namespace occsim::tune
