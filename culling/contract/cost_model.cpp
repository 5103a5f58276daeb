#include "occsim/culling/contract/cost_model.h"

#include <cmath>

namespace occsim {

bool CostModel::isValid(std::string* error) const {
    for (double v : {query_box_ms, triangle_ms, draw_call_ms}) {
        if (!(std::isfinite(v) && v >= 0.0)) {
            if (error) {
                *error =
                    "query_box_ms, triangle_ms and draw_call_ms must be finite numbers >= 0 "
                    "(milliseconds)";
            }
            return false;
        }
    }
    return true;
}

}  // namespace occsim
