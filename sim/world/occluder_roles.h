// What the scene says about occluders, counted for a person to check (`occsim info`, a run's
// header): per object its role (OccluderRole: chosen by size, always, never; from the scenario or
// a glTF node's extras.occsim_occluder) and whether someone authored its occluder mesh.
#pragma once

#include <cstdint>
#include <string>

#include "sim/world/world.h"

namespace occsim {

struct OccluderRoleCounts {
    uint32_t by_size = 0, always = 0, never = 0;
    uint32_t authored_meshes = 0;  // objects with an authored occluder mesh
};

OccluderRoleCounts countOccluderRoles(const Scene& scene);

// "248 by size, 11 always, 41 never; 2 with an authored occluder mesh".
std::string occluderRolesText(const OccluderRoleCounts& counts);

}  // namespace occsim
