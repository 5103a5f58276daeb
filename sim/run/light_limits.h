// What a device must offer for a scenario's lights (docs/views.md), checked before frame 0: each
// shadow map no larger than the device's largest texture. A run that asks for more is bad input,
// refused with one line naming the scenario file and the light's key.
#pragma once

#include <cstdint>

#include "sim/scenario/scenario.h"

namespace occsim {

// Throws ScenarioError at /lights/<i>/shadow_map for the first shadow-casting light whose map is
// larger than `max_texture_size` texels a side (GL_MAX_TEXTURE_SIZE).
void checkShadowMapsFit(const Scenario& scenario, uint32_t max_texture_size);

}  // namespace occsim
