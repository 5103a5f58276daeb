// The glTF scene source (sim/scene/gltf_source.h): the three real files in scenarios/assets load
// with the triangle and node counts of their README, instanced meshes are converted once,
// transforms and replication place objects where the contract says, and broken files fail with one
// line. Synthetic files are small JSON documents with a base64 data: URI buffer, built here.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "gltf_files.h"

namespace occsim {
namespace {

using nlohmann::json;
using namespace testing_gltf;

using namespace gltf_files;

// ---- The real files (their table and boxes, as the assets' SOURCE notes give them) ---------

TEST(GltfRealFiles, TeapotLoadsItsTrianglesOnOneNodeWithTheReadmeBounds) {
    const SourceOutput out = load(kTeapot);
    EXPECT_EQ(drawnTriangles(out), 9128u);
    EXPECT_EQ(out.objects.size(), 1u);
    EXPECT_EQ(out.meshes.size(), 1u);
    expectBoxNear(floatBox(out.region), {-30.4f, -17.2f, -20.0f}, {33.9f, 14.3f, 20.0f}, 0.1f);
    EXPECT_TRUE(out.warnings.empty()) << allWarnings(out);
    expectWellFormed(out);
}

TEST(GltfRealFiles, SubpassSceneLoadsSeventyNodesSharingTwelveMeshes) {
    const SourceOutput out = load(kSubpass);
    EXPECT_EQ(drawnTriangles(out), 23388u);
    EXPECT_EQ(out.objects.size(), 70u);
    EXPECT_EQ(out.meshes.size(), 12u);  // every node mirrors (scale -1), so one variant per mesh
    expectBoxNear(floatBox(out.region), {-11.0f, -9.7f, -11.0f}, {11.0f, 0.5f, 11.0f}, 0.1f);
    EXPECT_TRUE(out.warnings.empty()) << allWarnings(out);
    expectWellFormed(out);
}

TEST(GltfRealFiles, FzkHausGlbLoadsItsTrianglesOn110NodesSharing59Meshes) {
    const SourceOutput out = load(kHouse);
    EXPECT_EQ(drawnTriangles(out), 35906u);
    EXPECT_EQ(out.objects.size(), 110u);
    EXPECT_EQ(out.meshes.size(), 59u);
    expectBoxNear(floatBox(out.region), {-3.0f, -1.0f, -13.0f}, {15.0f, 6.3f, 3.0f}, 0.1f);
    EXPECT_TRUE(out.warnings.empty()) << allWarnings(out);
    expectWellFormed(out);
}

TEST(GltfRealFiles, MirroredNodesKeepFrontFacesCounterClockwise) {
    // Every node of the subpass scene has a negative scale. Its floor is a box; for each face of
    // the box, the world-space winding normal must point away from the box centre.
    const SourceOutput out = load(kSubpass);
    size_t checked = 0;
    for (const PlacedObject& o : out.objects) {
        const MeshData& mesh = out.meshes[o.mesh];
        ASSERT_LT(glm::determinant(o.linear), 0.0f);
        const glm::vec3 centre = o.linear * center(meshBounds(mesh));
        if (mesh.positions.size() > 64) continue;  // boxes only: convex, so the test is exact
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::vec3 a = o.linear * mesh.positions[mesh.indices[3 * t]];
            EXPECT_GT(glm::dot(worldFaceNormal(out, o, t), a - centre), 0.0f);
            ++checked;
        }
    }
    EXPECT_GT(checked, 0u);
}

// ---- Instancing, transforms, scenes --------------------------------------------------------

TEST(GltfScene, AMeshUsedBySeveralNodesIsConvertedOnce) {
    GltfBuilder b;
    const int mesh = b.triangleMesh("Shared");
    const int child = b.node({{"mesh", mesh}, {"translation", {0, 5, 0}}}, false);
    b.node({{"mesh", mesh}, {"translation", {10, 0, 0}}, {"children", {child}}});
    b.node({{"mesh", mesh}, {"translation", {-3, 0, 0}}});
    const SourceOutput out = loadText(b.text());
    ASSERT_EQ(out.objects.size(), 3u);
    EXPECT_EQ(out.meshes.size(), 1u);
    for (const PlacedObject& o : out.objects) EXPECT_EQ(o.mesh, 0u);
    std::set<std::array<double, 3>> positions;
    for (const PlacedObject& o : out.objects)
        positions.insert({o.position.x, o.position.y, o.position.z});
    const std::set<std::array<double, 3>> expected = {{10, 0, 0}, {10, 5, 0}, {-3, 0, 0}};
    EXPECT_EQ(positions, expected);  // the child's translation is added to its parent's
    expectWellFormed(out);
}

TEST(GltfScene, HierarchyComposesMatrixAndTrsWithScaleAndOffset) {
    GltfBuilder b;
    const int mesh = b.triangleMesh("Tri");
    // Child: rotated 90 degrees about y, scaled 2, translated (1, 0, 0) in the parent's frame.
    const double s = std::sqrt(0.5);
    const int child = b.node({{"mesh", mesh},
                              {"translation", {1, 0, 0}},
                              {"rotation", {0, s, 0, s}},
                              {"scale", {2, 2, 2}}},
                             false);
    // Parent: a column-major matrix translating by (0, 0, 4) and scaling by 3.
    b.node({{"matrix", {3, 0, 0, 0, 0, 3, 0, 0, 0, 0, 3, 0, 0, 0, 4, 1}}, {"children", {child}}});
    const SourceOutput out = loadText(b.text(), {}, 1, 0.5, {100, 0, 0});
    ASSERT_EQ(out.objects.size(), 1u);
    const PlacedObject& o = out.objects[0];
    // World = parent * child: translation (3, 0, 4); then the spec: * 0.5 and + (100, 0, 0).
    EXPECT_NEAR(o.position.x, 101.5, 1e-9);
    EXPECT_NEAR(o.position.y, 0.0, 1e-9);
    EXPECT_NEAR(o.position.z, 2.0, 1e-9);
    // Linear: 3 * 2 * 0.5 = 3 times a rotation taking +x to -z.
    const glm::vec3 x = o.linear * glm::vec3(1, 0, 0);
    EXPECT_NEAR(x.x, 0.0f, 1e-5f);
    EXPECT_NEAR(x.z, -3.0f, 1e-5f);
    EXPECT_NEAR(glm::determinant(o.linear), 27.0f, 1e-3f);
}

TEST(GltfScene, ANegativeDeterminantReversesTheWindingOfThatNodesCopy) {
    GltfBuilder b;
    const int mesh = b.triangleMesh("Tri");
    b.node({{"mesh", mesh}});
    b.node({{"mesh", mesh}, {"scale", {-1, 1, 1}}});
    const SourceOutput out = loadText(b.text());
    ASSERT_EQ(out.objects.size(), 2u);
    EXPECT_EQ(out.meshes.size(), 2u);  // as is, and mirrored
    EXPECT_NE(out.objects[0].mesh, out.objects[1].mesh);
    for (const PlacedObject& o : out.objects) {
        EXPECT_GT(worldFaceNormal(out, o, 0).z, 0.0f) << "still counter-clockwise from +z";
    }
}

TEST(GltfScene, UsesTheDefaultSceneElseAllRootNodes) {
    GltfBuilder b;
    const int mesh = b.triangleMesh("Tri");
    b.node({{"mesh", mesh}, {"translation", {1, 0, 0}}});  // root of scene 0
    const int child = b.node({{"mesh", mesh}, {"translation", {0, 1, 0}}}, false);
    const int other =
        b.node({{"mesh", mesh}, {"translation", {2, 0, 0}}, {"children", {child}}}, false);
    b.doc()["scenes"].push_back({{"nodes", {other}}});
    b.doc()["scene"] = 1;
    SourceOutput out = loadText(b.text());
    ASSERT_EQ(out.objects.size(), 2u);
    EXPECT_EQ(out.objects[0].position, glm::dvec3(2, 0, 0));
    EXPECT_EQ(out.objects[1].position, glm::dvec3(2, 1, 0));

    b.doc().erase("scene");  // scene 0 then
    EXPECT_EQ(loadText(b.text()).objects.size(), 1u);

    b.doc().erase("scenes");  // no scenes: every node that is no one's child
    EXPECT_EQ(loadText(b.text()).objects.size(), 3u);
}

TEST(GltfScene, ANodesExtrasGiveItsOccluderRole) {
    GltfBuilder b;
    const int mesh = b.triangleMesh("Tri");
    b.node({{"mesh", mesh}, {"extras", {{"occsim_occluder", "never"}}}});
    b.node({{"mesh", mesh}, {"extras", {{"occsim_occluder", "always"}, {"note", 1}}}});
    b.node({{"mesh", mesh}, {"extras", {{"other", "always"}}}});
    b.node({{"mesh", mesh}});
    const SourceOutput out = loadText(b.text());
    ASSERT_EQ(out.objects.size(), 4u);
    EXPECT_EQ(out.objects[0].occluder, OccluderRole::Never);
    EXPECT_EQ(out.objects[1].occluder, OccluderRole::Always);
    EXPECT_EQ(out.objects[2].occluder, std::nullopt);  // the source's role holds
    EXPECT_EQ(out.objects[3].occluder, std::nullopt);
}

// A node names a mesh of the file as its occluder: that mesh is output (here only for that; as
// is, or mirrored where the node is) and the object points at it.
TEST(GltfScene, ANodesExtrasNameItsOccluderMesh) {
    GltfBuilder b;
    const int tri = b.triangleMesh("Tri");
    const int inner = b.triangleMesh("Inner");
    b.node({{"mesh", tri}, {"extras", {{"occsim_occluder_mesh", inner}}}});
    b.node({{"mesh", tri}});
    b.node({{"mesh", tri}, {"scale", {-1, 1, 1}}, {"extras", {{"occsim_occluder_mesh", inner}}}});
    const SourceOutput out = loadText(b.text());
    ASSERT_EQ(out.objects.size(), 3u);
    ASSERT_TRUE(out.objects[0].occluder_mesh.has_value());
    EXPECT_NE(*out.objects[0].occluder_mesh, out.objects[0].mesh);
    EXPECT_LT(*out.objects[0].occluder_mesh, out.meshes.size());
    EXPECT_EQ(out.objects[1].occluder_mesh, std::nullopt);
    ASSERT_TRUE(out.objects[2].occluder_mesh.has_value());
    // The mirrored node's occluder is the mirrored output of the same mesh.
    EXPECT_NE(*out.objects[2].occluder_mesh, *out.objects[0].occluder_mesh);
    EXPECT_EQ(out.meshes.size(), 4u);  // Tri and Inner, each as is and mirrored
}

// ---- Primitives ----------------------------------------------------------------------------

TEST(GltfPrimitives, IndicesOfEveryWidthAndNonIndexedGiveTheSameTriangles) {
    const std::vector<glm::vec3> quad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const std::vector<uint32_t> order = {0, 1, 2, 0, 2, 3};
    std::vector<std::vector<glm::vec3>> results;
    for (int type : {kUnsignedByte, kUnsignedShort, kUnsignedInt, 0}) {
        GltfBuilder b;
        json primitive;
        if (type == 0) {
            std::vector<glm::vec3> soup;
            for (uint32_t i : order) soup.push_back(quad[i]);
            primitive = GltfBuilder::primitive(b.vec3(soup));
        } else {
            primitive = GltfBuilder::primitive(b.vec3(quad), b.indices(order, type));
        }
        b.node({{"mesh", b.mesh("Quad", json::array({primitive}))}});
        const SourceOutput out = loadText(b.text());
        expectWellFormed(out);
        std::vector<glm::vec3> corners;
        for (uint32_t i : out.meshes.at(0).indices) corners.push_back(out.meshes[0].positions[i]);
        results.push_back(corners);
    }
    for (size_t r = 1; r < results.size(); ++r)
        EXPECT_EQ(results[r], results[0]) << "variant " << r;
}

TEST(GltfPrimitives, ReadsPositionsThroughAByteStride) {
    GltfBuilder b;
    const int p = b.vec3({{0, 0, 0}, {2, 0, 0}, {0, 3, 0}}, 20);
    b.node({{"mesh", b.mesh("Strided", json::array({GltfBuilder::primitive(p)}))}});
    const SourceOutput out = loadText(b.text());
    const std::vector<glm::vec3> expected = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
    EXPECT_EQ(out.meshes.at(0).positions, expected);
}

TEST(GltfPrimitives, StripsAndFansBecomeCounterClockwiseTriangleLists) {
    GltfBuilder b;
    // Strip 0-1-2-3 over a unit square, fan around the centre of a square: all facing +z.
    const int strip = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
    const int fan = b.vec3({{0.5f, 0.5f, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    b.node({{"mesh", b.mesh("StripAndFan", json::array({GltfBuilder::primitive(strip, -1, kStrip),
                                                        GltfBuilder::primitive(fan, -1, kFan)}))}});
    const SourceOutput out = loadText(b.text());
    ASSERT_EQ(out.meshes.size(), 1u);
    EXPECT_EQ(out.meshes[0].triangleCount(), 2u + 3u);
    for (size_t t = 0; t < out.meshes[0].triangleCount(); ++t) {
        EXPECT_GT(worldFaceNormal(out, out.objects[0], t).z, 0.0f) << "triangle " << t;
    }
    expectWellFormed(out);
}

TEST(GltfPrimitives, ComputesNormalsWhenAbsentAndNormalisesGivenOnes) {
    GltfBuilder b;
    const int p = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int n = b.vec3({{0, 0, 2}, {0, 0, 3}, {0, 4, 0}});
    json with_normals = GltfBuilder::primitive(p);
    with_normals["attributes"]["NORMAL"] = n;
    b.node({{"mesh", b.mesh("Computed", json::array({GltfBuilder::primitive(p)}))}});
    b.node({{"mesh", b.mesh("Given", json::array({with_normals}))}});
    const SourceOutput out = loadText(b.text());
    ASSERT_EQ(out.meshes.size(), 2u);
    for (const glm::vec3& normal : out.meshes[0].normals) EXPECT_EQ(normal, glm::vec3(0, 0, 1));
    const std::vector<glm::vec3> given = {{0, 0, 1}, {0, 0, 1}, {0, 1, 0}};
    EXPECT_EQ(out.meshes[1].normals, given);
}

TEST(GltfPrimitives, MergesAllTrianglePrimitivesOfAMeshIntoOneMeshData) {
    GltfBuilder b;
    const int first = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int second = b.vec3({{0, 0, 5}, {1, 0, 5}, {0, 1, 5}});
    b.node({{"mesh",
             b.mesh("Two", json::array({GltfBuilder::primitive(first, b.indices({0, 1, 2})),
                                        GltfBuilder::primitive(second, b.indices({0, 1, 2}))}))}});
    const SourceOutput out = loadText(b.text());
    ASSERT_EQ(out.meshes.size(), 1u);
    EXPECT_EQ(out.meshes[0].positions.size(), 6u);
    const std::vector<uint32_t> indices = {0, 1, 2, 3, 4, 5};
    EXPECT_EQ(out.meshes[0].indices, indices);
}

TEST(GltfPrimitives, SkipsLinesBesideTrianglesWithAWarningNamingTheMesh) {
    GltfBuilder b;
    const int p = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int lines = b.vec3({{0, 0, 0}, {1, 1, 1}});
    b.node({{"mesh", b.mesh("Fence", json::array({GltfBuilder::primitive(p),
                                                  GltfBuilder::primitive(lines, -1, kLines),
                                                  GltfBuilder::primitive(lines, -1, kLines)}))}});
    const SourceOutput out = loadText(b.text());
    EXPECT_EQ(out.meshes.at(0).triangleCount(), 1u);
    ASSERT_EQ(out.warnings.size(), 1u) << allWarnings(out);
    EXPECT_NE(
        out.warnings[0].find("model.gltf: skipped 2 primitives with mode LINES in mesh 'Fence'"),
        std::string::npos)
        << out.warnings[0];
}

TEST(GltfPrimitives, WarnsAboutMorphTargetsSparseAndQuantizedPositionsAndSkins) {
    GltfBuilder b;
    const int p = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    json morphed = GltfBuilder::primitive(p);
    morphed["targets"] = json::array({{{"POSITION", b.vec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}})}}});
    json sparse_accessor = b.doc()["accessors"][p];
    sparse_accessor["sparse"] = {{"count", 1},
                                 {"indices", {{"bufferView", 0}, {"componentType", kUnsignedInt}}},
                                 {"values", {{"bufferView", 0}}}};
    const int sparse = b.addAccessor(sparse_accessor);
    json quantized_accessor = b.doc()["accessors"][p];
    quantized_accessor["componentType"] = kUnsignedShort;
    quantized_accessor["normalized"] = true;
    const int quantized = b.addAccessor(quantized_accessor);
    b.node({{"mesh", b.mesh("Odd", json::array({morphed, GltfBuilder::primitive(sparse),
                                                GltfBuilder::primitive(quantized)}))}});
    b.doc()["skins"] = json::array({{{"joints", {0}}}});
    b.doc()["nodes"][0]["skin"] = 0;
    const SourceOutput out = loadText(b.text());
    EXPECT_EQ(out.meshes.at(0).triangleCount(), 1u);  // the morphed primitive's base positions
    EXPECT_TRUE(anyWarningContains(out, "with morph targets in mesh 'Odd'")) << allWarnings(out);
    EXPECT_TRUE(anyWarningContains(out, "1 primitive with sparse accessors")) << allWarnings(out);
    EXPECT_TRUE(anyWarningContains(out, "1 primitive with quantized")) << allWarnings(out);
    EXPECT_TRUE(anyWarningContains(out, "skins")) << allWarnings(out);
}

TEST(GltfPrimitives, OnlyLinesAndPointsIsAnErrorSayingNoTriangles) {
    GltfBuilder b;
    const int lines = b.vec3({{0, 0, 0}, {1, 1, 1}});
    b.node({{"mesh", b.mesh("Wire", json::array({GltfBuilder::primitive(lines, -1, kLines),
                                                 GltfBuilder::primitive(lines, -1, kPoints)}))}});
    const std::string error = errorOfText(b.text());
    EXPECT_NE(error.find("model.gltf: no triangles"), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

TEST(GltfPrimitives, RequiredGeometryExtensionsFailAppearanceOnesDoNot) {
    GltfBuilder b;
    b.node({{"mesh", b.triangleMesh("Tri")}});
    b.doc()["extensionsUsed"] = {"KHR_materials_unlit"};
    b.doc()["extensionsRequired"] = {"KHR_materials_unlit"};
    EXPECT_EQ(loadText(b.text()).objects.size(), 1u);
    b.doc()["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    b.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    const std::string error = errorOfText(b.text());
    EXPECT_NE(error.find("requires the unsupported extension 'KHR_draco_mesh_compression'"),
              std::string::npos)
        << error;
}

// ---- Through the scenario and the scene builder --------------------------------------------

TEST(GltfScenario, TheGltfHouseScenarioBuildsItsGridAndMovers) {
    const std::filesystem::path file =
        std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/gltf-house.json";
    const Scenario scenario = parseScenarioFile(file);
    const Scene scene = buildScene(scenario);
    const auto& spec = std::get<GltfSourceSpec>(scenario.sources.at(0).spec);
    const uint32_t copies = spec.replicate.count_x * spec.replicate.count_z;
    EXPECT_GE(copies, 4u);
    EXPECT_GT(scene.objectCount(), copies * 110u);  // the houses, and spawned movers
    EXPECT_FALSE(scene.initial_movers.empty());
    EXPECT_TRUE(scene.warnings.empty());
}

// A scenario of these sources seen from (0, 0, 5), as a file's JSON.
json scenarioOfSources(const json& sources) {
    return {{"format_version", 1},
            {"camera",
             {{"keyframes", {{{"time", 0}, {"position", {0, 0, 5}}, {"target", {0, 0, 0}}}}}}},
            {"scene", {{"sources", sources}}}};
}

TEST(GltfScenario, WarningsReachTheScene) {
    GltfBuilder b;
    const int p = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    b.node({{"mesh", b.mesh("Fence", json::array({GltfBuilder::primitive(p),
                                                  GltfBuilder::primitive(p, -1, kPoints)}))}});
    TempDir dir;
    dir.write("model.gltf", b.text());
    const json scenario = scenarioOfSources({{{"type", "gltf"}, {"path", "model.gltf"}}});
    const std::filesystem::path file = dir.write("scenario.json", scenario.dump());
    const Scene scene = buildScene(parseScenarioFile(file));
    EXPECT_EQ(scene.objectCount(), 1u);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_NE(scene.warnings[0].find("mode POINTS in mesh 'Fence'"), std::string::npos);
}

// A source's role reaches each of its objects; a node's own extras win over it.
TEST(GltfScenario, OccluderRolesReachTheScenePerObject) {
    GltfBuilder b;
    const int mesh = b.triangleMesh("Tri");
    b.node({{"mesh", mesh}});
    b.node({{"mesh", mesh}, {"extras", {{"occsim_occluder", "always"}}}});
    TempDir dir;
    dir.write("model.gltf", b.text());
    const json scenario =
        scenarioOfSources({{{"type", "gltf"}, {"path", "model.gltf"}, {"occluders", "never"}},
                           {{"type", "teapots"}, {"count", 2}}});
    const Scene scene = buildScene(parseScenarioFile(dir.write("scenario.json", scenario.dump())));
    ASSERT_EQ(scene.objectCount(), 4u);
    ASSERT_EQ(scene.object_occluder.size(), 4u);
    EXPECT_EQ(scene.object_occluder[0], OccluderRole::Never);
    EXPECT_EQ(scene.object_occluder[1], OccluderRole::Always);
    EXPECT_EQ(scene.object_occluder[2], OccluderRole::BySize);
    EXPECT_EQ(scene.object_occluder[3], OccluderRole::BySize);
}

// A path that names a folder is not "no such file": the message says what it found.
TEST(GltfScenario, APathThatIsAFolderSaysSo) {
    TempDir dir;
    std::filesystem::create_directories(dir.path() / "models.gltf");
    const json scenario = scenarioOfSources({{{"type", "gltf"}, {"path", "models.gltf"}}});
    const std::filesystem::path file = dir.write("scenario.json", scenario.dump());
    try {
        parseScenarioFile(file);
        ADD_FAILURE() << "expected a ScenarioError";
    } catch (const ScenarioError& e) {
        const std::string message = e.what();
        EXPECT_NE(
            message.find("/scene/sources/0/path: expected a .gltf or .glb file, got a directory"),
            std::string::npos)
            << message;
    }
}

}  // namespace
}  // namespace occsim
