// What several of the tuner's test files share: a seeded normal variate, the paper's culler, and
// the settings of a small sample log.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "occsim/culling/geometry/random.h"
#include "occsim/culling/registry/registry.h"
#include "tune/design.h"
#include "tune/sample_log.h"

namespace occsim::tune::fixtures {

// A standard normal variate (Box-Muller) from the project's seeded generator.
inline double gaussian(Rng& rng) {
    const double u = std::max(rng.uniform(), 1e-12);
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * 3.14159265358979323846 * rng.uniform());
}

// A bowl with its minimum inside the cube at (0.3, 0.7, 0.5) and a cross term.
inline double trueResponse(const Point& x) {
    const double a = x[0] - 0.3, b = x[1] - 0.7, c = x[2] - 0.5;
    return 0.9 + 0.4 * a * a + 0.3 * b * b + 0.2 * c * c + 0.1 * a * b;
}

struct Data {
    std::vector<Point> xs;
    std::vector<double> ys;
};

inline Data responseData(size_t n, double noise, uint64_t seed, double (*f)(const Point&)) {
    Data d;
    d.xs = latinHypercube(n, 3, seed);
    Rng rng(seed + 100);
    for (const Point& x : d.xs) d.ys.push_back(f(x) + noise * gaussian(rng));
    return d;
}

inline const CullerRow& statistical() { return *findCuller("statistical"); }

// A sample log's settings: one parameter of the statistical culler, a short run.
inline LogSettings settings() {
    LogSettings s;
    s.scenario_file = "a.json";
    s.scenario_name = "a";
    s.scenario_hash = textHash("{}");
    s.parameters = {"base_time"};
    s.bounds = {{0.1, 2.0}};
    s.frames = 20;
    s.warmup_frames = 5;
    s.seed = 3;
    s.initial_samples = 5;
    return s;
}

}  // namespace occsim::tune::fixtures
