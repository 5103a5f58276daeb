// The frame-time model: a frame's time explained by what it did,
//
//   frame_ms = constant_ms + query_ms * queries + kilotriangle_ms * triangles / 1000
//            + draw_call_ms * objects_drawn + wait_factor * wait_ms,
//
// fitted (Ceres, Huber loss, every coefficient >= 0: doing more never makes a frame cheaper) over
// every timed frame of every run of a tuning session. Its figures are what a culler needs to tell
// whether a query can pay (a node cheaper to draw than to query), as Guthe, Balázs & Klein do
// with costs measured at start-up ("Near Optimal Hierarchical Culling", EGSR 2006).
//
// Not occsim::CostModel (occsim/culling/contract/cost_model.h), the per-box, per-triangle and
// per-draw costs a culler reads; tuned_file.h turns this model into one. Where the figures are the
// same the names are: draw_call_ms is the same figure in both. query_ms is per query (one box, or
// one multiquery's boxes), which the cost model takes as its query_box_ms; kilotriangle_ms is per
// thousand triangles (better conditioned in the fit), triangleMs() per triangle as triangle_ms is.
// cost_model.json keeps its key names (query_ms, draw_ms, ...): tools read them.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "tune/robust_fit.h"

namespace occsim::tune {

// One frame's figures (sim/run/frame_stats.h: FrameStats).
struct FrameCounts {
    double frame_ms = 0.0;
    double queries = 0.0;
    double triangles = 0.0;
    double objects_drawn = 0.0;  // one draw call per object
    double wait_ms = 0.0;        // blocked on query results, inside frame_ms
};

struct FrameTimeModel {
    static constexpr size_t kTerms = 5;
    double constant_ms = 0.0;
    double query_ms = 0.0;         // per query (one box, or one multiquery's boxes)
    double kilotriangle_ms = 0.0;  // per thousand drawn triangles
    double draw_call_ms = 0.0;     // per draw call
    double wait_factor = 0.0;      // per waited millisecond (1 = waiting adds exactly its time)

    double predict(const FrameCounts& f) const;
    double triangleMs() const { return kilotriangle_ms / 1000.0; }
};

struct FrameTimeModelFit {
    FrameTimeModel model;
    RobustFit fit;  // converged, Ceres' summary line
    size_t frames = 0;
    size_t groups = 0;  // runs the frames came from
    double mean_frame_ms = 0.0;
    double residual_rms_ms = 0.0;  // over the frames fitted
    // Prediction error on frames left out of the fit: each run's frames are predicted by a fit
    // without that run (5 folds of whole runs); NaN with fewer than 2 runs.
    double heldout_rms_ms = 0.0;
    // Approximate standard errors of the coefficients (least-squares formula at the robust fit).
    std::array<double, FrameTimeModel::kTerms> standard_error{};
};

// groups: the frames of each run (sample or reference). Needs at least kTerms frames.
FrameTimeModelFit fitFrameTimeModel(const std::vector<std::vector<FrameCounts>>& groups,
                                    int max_iterations = 200);

}  // namespace occsim::tune
