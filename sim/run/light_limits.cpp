// See light_limits.h.
#include "sim/run/light_limits.h"

#include <string>

namespace occsim {

void checkShadowMapsFit(const Scenario& scenario, uint32_t max_texture_size) {
    for (size_t i = 0; i < scenario.lights.size(); ++i) {
        const LightSpec& light = scenario.lights[i];
        if (!light.casts_shadows || light.shadow_map <= max_texture_size) continue;
        throw ScenarioError(scenario.file.string(), "/lights/" + std::to_string(i) + "/shadow_map",
                            "expected at most " + std::to_string(max_texture_size) +
                                " (this device's largest texture, a side in texels), got " +
                                std::to_string(light.shadow_map));
    }
}

}  // namespace occsim
