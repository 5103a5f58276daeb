#include "sim/world/occluder_roles.h"

namespace occsim {

OccluderRoleCounts countOccluderRoles(const Scene& scene) {
    OccluderRoleCounts c;
    const uint32_t meshes = static_cast<uint32_t>(scene.meshes.size());
    for (uint32_t o = 0; o < scene.objectCount(); ++o) {
        // An object the sources gave no role is chosen by size (SharedWorld reads it so).
        const OccluderRole role =
            o < scene.object_occluder.size() ? scene.object_occluder[o] : OccluderRole::BySize;
        switch (role) {
            case OccluderRole::BySize:
                ++c.by_size;
                break;
            case OccluderRole::Always:
                ++c.always;
                break;
            case OccluderRole::Never:
                ++c.never;
                break;
        }
        if (o < scene.object_occluder_mesh.size() && scene.object_occluder_mesh[o] < meshes)
            ++c.authored_meshes;
    }
    return c;
}

std::string occluderRolesText(const OccluderRoleCounts& c) {
    return std::to_string(c.by_size) + " by size, " + std::to_string(c.always) + " always, " +
           std::to_string(c.never) + " never; " + std::to_string(c.authored_meshes) +
           " with an authored occluder mesh";
}

}  // namespace occsim
