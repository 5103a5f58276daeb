#include "sim/run/culler_setup.h"

#include "occsim/culling/contract/render_device.h"
#include "render/gl_renderer.h"

namespace occsim {

std::optional<CostModelChoice> chooseCostModel(std::vector<RunConfig>& configs, const Scene& scene,
                                               const Scenario& scenario, GlRenderer& renderer,
                                               const LatencyMode& latency) {
    std::optional<CostModelChoice> choice;
    for (RunConfig& config : configs) {
        const CullerRow& algorithm = *config.algorithm;
        if (!algorithm.cost_model_use) continue;
        const CostModelUse use = algorithm.cost_model_use(config.culler.of(algorithm));
        if (!use.wanted) continue;
        // A cost model given for this culler alone wins over the shared one.
        if (const auto it = config.culler.cost_model_of.find(algorithm.name);
            it != config.culler.cost_model_of.end()) {
            config.culler.cost_model = it->second;
        }
        if (config.culler.cost_model.known()) {
            if (!choice)
                choice = CostModelChoice{config.culler.cost_model, CostModelSource::Scenario};
            continue;
        }
        if (!choice || choice->source == CostModelSource::Scenario) {
            // Queries are timed with as many in flight as this culler keeps.
            choice = latency.deterministic
                         ? CostModelChoice{referenceCostModel(), CostModelSource::Reference}
                         : CostModelChoice{
                               calibrateCostModel(scene, scenario, renderer, use.queries_in_flight),
                               CostModelSource::Calibrated};
        }
        config.culler.cost_model = choice->costs;
    }
    return choice;
}

std::unique_ptr<Culler> makeConfiguredCuller(const RunConfig& config) {
    return makeCuller(*config.algorithm, config.culler);
}

}  // namespace occsim
