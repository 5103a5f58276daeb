// The world every culler of a run shares (sim/run/shared_world.h): flat mesh arrays for the
// cullers, transforms that follow the movers, and occluder meshes checked against their objects.
#include <gtest/gtest.h>

#include "gltf_builder.h"
#include "sim/run/shared_world.h"
#include "small_scenario.h"

namespace occsim {
namespace {

using testing::smallScenario;

// What a culler with needs_meshes gets (CullFrame::meshes): every mesh once, and per frame each
// object's transform into the culling frame, which puts its mesh inside its world box.
TEST(SharedWorld, MeshesForCullersAreFlatArraysAndTransformsFollowTheMovers) {
    Scenario s = smallScenario();
    auto& teapots = std::get<TeapotFieldSpec>(s.sources[0].spec);
    teapots.region = {glm::vec3(999980, 0, 4950), glm::vec3(1000020, 5, 5000)};
    s.camera.keyframes = {{0.0, {999990.2, 2, 5010}, {1e6, 1, 4975}}};
    s.frames = 3;
    const Scene scene = buildScene(s);
    SharedWorld world(scene, s);
    for (uint32_t frame = 0; frame < 3; ++frame) {
        world.advance();
        const CullMeshes& m = world.cullMeshes();
        ASSERT_EQ(m.meshes.size(), scene.meshes.size());
        ASSERT_EQ(m.object_mesh.size(), scene.objectCount());
        ASSERT_EQ(m.object_to_culling.size(), scene.objectCount());
        for (uint32_t o = 0; o < scene.objectCount(); o += 7) {
            const MeshRange& r = m.meshes[m.object_mesh[o]];
            EXPECT_EQ(r.index_count, scene.meshes[scene.object_mesh[o]].indices.size());
            const Aabb& box = world.state().boxes[o];
            for (uint32_t v = 0; v < r.vertex_count; v += 13) {
                const glm::vec4 p =
                    m.object_to_culling[o] * glm::vec4(m.positions[r.first_vertex + v], 1.0f);
                for (int axis = 0; axis < 3; ++axis) {
                    EXPECT_GE(p[axis], box.min[axis] - 1e-3f) << o;
                    EXPECT_LE(p[axis], box.max[axis] + 1e-3f) << o;
                }
            }
        }
    }
}

// The teapot's mesh is open, so it gets no inscribed occluder mesh: one line says which mesh,
// whose objects, and why; made once, before any frame's timing.
TEST(SharedWorld, AMeshWithoutAnInscribedOccluderIsNamedWithWhyInOneLine) {
    Scenario s = smallScenario();
    const Scene scene = buildScene(s);
    SharedWorld world(scene, s);
    world.advance();
    const CullMeshes& m = world.cullMeshes();
    const SharedWorld::OccluderMeshCost& cost = world.occluderMeshCost();
    EXPECT_EQ(cost.tried, 1u);
    EXPECT_EQ(cost.made, 0u);
    ASSERT_EQ(cost.refusals.size(), 1u);
    const std::string& line = cost.refusals[0];
    EXPECT_EQ(line.find('\n'), std::string::npos) << line;
    EXPECT_EQ(line.rfind("mesh 0 (of '", 0), 0u) << line;
    EXPECT_NE(line.find("has no inscribed occluder mesh: "), std::string::npos) << line;
    EXPECT_NE(line.find("not closed"), std::string::npos) << line;
    EXPECT_NE(line.find("own mesh in masked"), std::string::npos) << line;
    for (uint32_t o = 0; o < scene.objectCount(); ++o)
        EXPECT_EQ(m.object_occluder_mesh[o], kNoOccluderMesh) << o;
}

// A glTF node's own occluder mesh reaches the culler once checked against its object: a box
// inside the node's box stands in for it; one beside it is refused with a line naming the object,
// which then occludes with its own mesh.
TEST(SharedWorld, AGltfNodesOccluderMeshIsCheckedAgainstItsObject) {
    using nlohmann::json;
    using testing_gltf::GltfBuilder;
    using testing_gltf::TempDir;
    GltfBuilder b;
    auto box = [&](const std::string& name, float half, float dx) {
        std::vector<glm::vec3> corners;
        for (int i = 0; i < 8; ++i) {
            corners.emplace_back(dx + (i & 1 ? half : -half), i & 2 ? half : -half,
                                 i & 4 ? half : -half);
        }
        // Each face counter-clockwise seen from outside.
        const uint32_t quads[] = {0, 4, 6, 2, 1, 3, 7, 5, 0, 1, 5, 4,
                                  2, 6, 7, 3, 0, 2, 3, 1, 4, 5, 7, 6};
        std::vector<uint32_t> triangles;
        for (int q = 0; q < 24; q += 4) {
            triangles.insert(triangles.end(), {quads[q], quads[q + 1], quads[q + 2], quads[q],
                                               quads[q + 2], quads[q + 3]});
        }
        return b.mesh(name,
                      json::array({GltfBuilder::primitive(b.vec3(corners), b.indices(triangles))}));
    };
    const int outer = box("Outer", 1.0f, 0.0f), inner = box("Inner", 0.5f, 0.0f),
              beside = box("Beside", 0.5f, 3.0f);
    b.node({{"mesh", outer}, {"name", "Kept"}, {"extras", {{"occsim_occluder_mesh", inner}}}});
    b.node({{"mesh", outer},
            {"name", "Refused"},
            {"translation", {10, 0, 0}},
            {"extras", {{"occsim_occluder_mesh", beside}}}});
    TempDir dir;
    Scenario s = smallScenario();
    s.sources.clear();
    SceneSourceSpec& source = s.sources.emplace_back();
    source.type = SourceType::Gltf;
    GltfSourceSpec gltf;
    gltf.path = dir.write("model.gltf", b.text());
    source.spec.emplace<GltfSourceSpec>(gltf);
    s.movers.clear();
    const Scene scene = buildScene(s);
    ASSERT_EQ(scene.objectCount(), 2u);
    SharedWorld world(scene, s);
    world.advance();
    const CullMeshes& m = world.cullMeshes();
    ASSERT_NE(m.object_occluder_mesh[0], kNoOccluderMesh);
    EXPECT_EQ(m.meshes[m.object_occluder_mesh[0]].index_count, 36u);  // the inner box, whole
    EXPECT_EQ(m.object_occluder_mesh[1], kNoOccluderMesh);
    const SharedWorld::OccluderMeshCost& cost = world.occluderMeshCost();
    EXPECT_EQ(cost.tried, 2u);
    EXPECT_EQ(cost.made, 1u);
    ASSERT_EQ(cost.refusals.size(), 1u);
    EXPECT_NE(cost.refusals[0].find("the occluder mesh of 'Refused' (mesh "), std::string::npos)
        << cost.refusals[0];
    EXPECT_NE(cost.refusals[0].find("none of its 12 triangles lies inside its object; it "
                                    "occludes with its own mesh"),
              std::string::npos)
        << cost.refusals[0];
}

}  // namespace
}  // namespace occsim
