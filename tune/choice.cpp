#include "tune/choice.h"

#include <cmath>

namespace occsim::tune {
namespace {

// The integer the culler will run for a tuned integer option (ParameterSpace::apply rounds): the
// nearest one within the search box, so that the report, the console and confirmation.json give
// the value the confirmation ran, and a tuned value stays within its bounds.
double integerWithin(double value, const Bounds& b) {
    double v = std::round(value);
    if (v > b.hi) v = std::floor(b.hi);
    if (v < b.lo) v = std::ceil(b.lo);
    return v <= b.hi ? v : std::round(value);  // no integer in the box: what apply() runs
}

}  // namespace

void chooseTunedValues(TuneResult& r, const ParameterSpace& space) {
    const Point paper_unit = space.paperUnitPoint();
    r.tuned_unit = minimiseOverBox(r.response.model, paper_unit);
    r.tuned_values = space.values(r.tuned_unit);
    r.kept_at_paper.assign(space.size(), true);
    for (size_t j : r.response.model.active) r.kept_at_paper[j] = false;
    // Which optima lie on a bound, before an integer is rounded off it (18.6 -> 18 is still the
    // upper bound's doing).
    r.bounds_hit = space.boundsHit(r.tuned_values);
    bool rounded = false;
    for (size_t j = 0; j < space.size(); ++j) {
        if (r.kept_at_paper[j]) {
            r.tuned_values[j] = space.parameters[j].paper_value;
            r.bounds_hit[j].clear();
        } else if (space.parameters[j].integer) {
            r.tuned_values[j] = integerWithin(r.tuned_values[j], space.bounds[j]);
            rounded = true;
        }
    }
    // The predictions below are at the point the confirmation runs.
    if (rounded) {
        const Point applied = space.unitPoint(r.tuned_values);
        for (size_t j : r.response.model.active) r.tuned_unit[j] = applied[j];
    }
    r.predicted_tuned = r.response.model.predict(r.tuned_unit);
    r.predicted_tuned_sd = r.response.predict(r.tuned_unit).stddev;
    r.predicted_paper = r.response.model.predict(paper_unit);
}

}  // namespace occsim::tune
