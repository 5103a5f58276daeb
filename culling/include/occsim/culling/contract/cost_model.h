// What drawing and querying cost on the renderer at hand, in milliseconds: the per-frame cost
// model of the brief's "Cost model" section, in the spirit of the start-up measurements of Guthe,
// Balazs & Klein, "Near Optimal Hierarchical Culling" (EGSR 2006), section 4. Drawing an object
// costs draw_call_ms + triangles * triangle_ms; a query costs query_box_ms per box it rasterises.
// Plain data: measured at start-up by the run layer (sim/run/calibration.h), or given in a
// scenario as culling.cost_model {"query_box_ms", "triangle_ms", "draw_call_ms"}, e.g. by the
// tuner. All zero means "not known": cullers then ignore it.
#pragma once

#include <cstdint>
#include <string>

namespace occsim {

struct CostModel {
    double query_box_ms = 0.0;
    double triangle_ms = 0.0;
    double draw_call_ms = 0.0;

    bool known() const { return query_box_ms > 0.0 || triangle_ms > 0.0 || draw_call_ms > 0.0; }
    double drawMs(uint64_t triangles) const {
        return draw_call_ms + static_cast<double>(triangles) * triangle_ms;
    }
    // Every figure finite and >= 0.
    bool isValid(std::string* error) const;
    bool operator==(const CostModel&) const = default;
};

}  // namespace occsim
