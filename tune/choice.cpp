#include "tune/choice.h"

namespace occsim::tune {

void chooseTunedValues(TuneResult& r, const ParameterSpace& space) {
    const Point paper_unit = space.paperUnitPoint();
    r.tuned_unit = minimiseOverBox(r.response.model, paper_unit);
    r.tuned_values = space.values(r.tuned_unit);
    r.kept_at_paper.assign(space.size(), true);
    for (size_t j : r.response.model.active) r.kept_at_paper[j] = false;
    for (size_t j = 0; j < space.size(); ++j) {
        if (r.kept_at_paper[j]) r.tuned_values[j] = space.parameters[j].paper_value;
    }
    r.bounds_hit = space.boundsHit(r.tuned_values);
    for (size_t j = 0; j < space.size(); ++j) {
        if (r.kept_at_paper[j]) r.bounds_hit[j].clear();
    }
    r.predicted_tuned = r.response.model.predict(r.tuned_unit);
    r.predicted_tuned_sd = r.response.predict(r.tuned_unit).stddev;
    r.predicted_paper = r.response.model.predict(paper_unit);
}

}  // namespace occsim::tune
