// The occluder roles counted for `occsim info` and a run's header (sim/world/occluder_roles.h):
// each object counted once by its role, an object without one chosen by size, and the authored
// occluder meshes that name a mesh of the scene.
#include <gtest/gtest.h>

#include "sim/world/occluder_roles.h"

namespace occsim {
namespace {

Scene sceneOf(std::vector<OccluderRole> roles, std::vector<uint32_t> authored, uint32_t objects) {
    Scene scene;
    scene.meshes.resize(2);
    scene.object_mesh.assign(objects, 0);
    scene.object_occluder = std::move(roles);
    scene.object_occluder_mesh = std::move(authored);
    return scene;
}

TEST(OccluderRoles, CountsEachObjectOnceByItsRole) {
    const Scene scene = sceneOf({OccluderRole::Always, OccluderRole::Never, OccluderRole::Never,
                                 OccluderRole::BySize, OccluderRole::Always},
                                {kNoAuthoredOccluder, 1, kNoAuthoredOccluder, 1, 7}, 5);
    const OccluderRoleCounts c = countOccluderRoles(scene);
    EXPECT_EQ(c.always, 2u);
    EXPECT_EQ(c.never, 2u);
    EXPECT_EQ(c.by_size, 1u);
    EXPECT_EQ(c.authored_meshes, 2u) << "mesh 7 is no mesh of the scene: not counted";
    EXPECT_EQ(occluderRolesText(c),
              "1 by size, 2 always, 2 never; 2 with an authored occluder mesh");
}

TEST(OccluderRoles, AnObjectWithoutARoleIsChosenBySize) {
    const OccluderRoleCounts c = countOccluderRoles(sceneOf({OccluderRole::Never}, {}, 3));
    EXPECT_EQ(c.never, 1u);
    EXPECT_EQ(c.by_size, 2u);
    EXPECT_EQ(c.authored_meshes, 0u);
}

}  // namespace
}  // namespace occsim
