// The cost model of the statistical+ culler (CostModel, occsim/culling/contract/cost_model.h),
// measured on the renderer at hand before the first frame: a few timed draws and queries from the
// scenario's first view, in the spirit of the start-up measurements of Guthe, Balazs & Klein, "Near
// Optimal Hierarchical Culling" (EGSR 2006), section 4.
#pragma once

#include <string>

#include "occsim/culling/registry/culler_options.h"
#include "render/gl_renderer.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"

namespace occsim {

// Where a run's cost model came from: given by the scenario, measured before the first frame, or
// the fixed reference figures of deterministic-latency runs (referenceCostModel()).
enum class CostModelSource { Scenario, Calibrated, Reference };

// The word summary.json and report.md write for it: "scenario", "calibrated" or "reference".
inline const char* costModelSourceName(CostModelSource source) {
    switch (source) {
        case CostModelSource::Scenario:
            return "scenario";
        case CostModelSource::Calibrated:
            return "calibrated";
        case CostModelSource::Reference:
            return "reference";
    }
    return "unknown";
}

struct CostModelChoice {
    CostModel costs;
    CostModelSource source = CostModelSource::Scenario;
};

// Fixed figures for runs whose decisions must not depend on the machine (deterministic latency)
// when the scenario gives no cost model: a teapot of 992 triangles at 0.063 ms (the idle
// development machine's VFC time per object on scenarios/teapots.json) and a query box at the
// ratio to it that calibrateCostModel() measured there (0.1 to 0.14).
CostModel referenceCostModel();

// Times drawing a sample of the objects in the scenario's first view and querying the boxes of
// the BSP tree's nodes in that view, each measured a few times after a run that is thrown away,
// the fastest kept. Queries are timed the way the culler issues them: with at most
// `queries_in_flight` unanswered (each answer fetched before the next query past that), 0 = all
// issued before the first answer is fetched. On llvmpipe an answer costs a flush and a wait for
// the rasteriser, so a query costs the culler more than the throughput of queries alone. Needs
// the scene's meshes uploaded to the renderer. Drawing is split into a per-call and a
// per-triangle part by timing the meshes with fewer and more triangles
// separately; a scene whose meshes all have one triangle count charges everything to triangles.
// Costs some 150 ms of rendering, outside every timing. Leaves the renderer's framebuffer dirty.
CostModel calibrateCostModel(const Scene& scene, const Scenario& scenario, GlRenderer& renderer,
                             uint32_t queries_in_flight = 0);

}  // namespace occsim
