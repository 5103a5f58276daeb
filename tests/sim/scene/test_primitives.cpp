// The primitives the generators build from (sim/scene/primitives.h): boxes, cylinders and spheres
// as valid closed meshes with outward faces and the volumes they should have; boxes appended and
// placed where they are asked for.
#include <gtest/gtest.h>

#include <string>

#include "mesh_checks.h"
#include "sim/scene/primitives.h"

namespace occsim {
namespace {

using testing::expectFaceNormalsAgree;
using testing::expectValidMesh;
using testing::objectBox;
using testing::signedVolume;

TEST(Primitives, BoxHasTwelveOutwardTrianglesStandingOnTheGround) {
    const MeshData box = makeBox({2, 3, 4});
    EXPECT_EQ(box.triangleCount(), 12u);
    EXPECT_EQ(box.positions.size(), 24u);
    expectValidMesh(box, "box");
    expectFaceNormalsAgree(box);
    EXPECT_NEAR(signedVolume(box), 24.0, 1e-4);
    const Aabb b = meshBounds(box);
    EXPECT_EQ(b.min, glm::vec3(-1, 0, -2));
    EXPECT_EQ(b.max, glm::vec3(1, 3, 2));
}

TEST(Primitives, CylinderHasFourTrianglesPerSegmentAndOutwardFaces) {
    for (uint32_t segments : {3u, 12u, 16u}) {
        const MeshData c = makeCylinder(0.5f, 2.0f, segments);
        EXPECT_EQ(c.triangleCount(), 4 * segments);
        expectValidMesh(c, "cylinder " + std::to_string(segments));
        expectFaceNormalsAgree(c);
        // The inscribed polygon's area times the height.
        const double area = 0.5 * segments * 0.25 * std::sin(2 * 3.14159265358979 / segments);
        EXPECT_NEAR(signedVolume(c), area * 2.0, 1e-4);
        EXPECT_NEAR(meshBounds(c).min.y, 0.0f, 1e-6f);
        EXPECT_NEAR(meshBounds(c).max.y, 2.0f, 1e-6f);
    }
    EXPECT_THROW(makeCylinder(1, 1, 2), std::invalid_argument);
}

TEST(Primitives, SphereHasTwoTrianglesPerSegmentAndRingBetweenPolesAndOutwardFaces) {
    for (auto [segments, rings] : {std::pair{3u, 2u}, std::pair{16u, 8u}, std::pair{24u, 12u}}) {
        const MeshData s = makeSphere(1.5f, segments, rings);
        EXPECT_EQ(s.triangleCount(), 2 * segments * (rings - 1));
        expectValidMesh(s, "sphere " + std::to_string(segments) + "x" + std::to_string(rings));
        expectFaceNormalsAgree(s);
        EXPECT_NEAR(meshBounds(s).min.y, 0.0f, 1e-5f);
        EXPECT_NEAR(meshBounds(s).max.y, 3.0f, 1e-5f);
    }
    // Fine enough, the volume approaches the sphere's.
    EXPECT_NEAR(signedVolume(makeSphere(1.0f, 64, 32)), 4.0 / 3.0 * 3.14159265358979, 0.03);
    EXPECT_THROW(makeSphere(1, 8, 1), std::invalid_argument);
}

TEST(Primitives, AppendBoxSpansItsCornersAndStaysClosed) {
    MeshData m;
    appendBox(m, {1, 2, 3}, {2, 4, 7});
    appendBox(m, {-1, -1, -1}, {0, 0, 0});
    EXPECT_EQ(m.triangleCount(), 24u);
    expectValidMesh(m, "two boxes");
    expectFaceNormalsAgree(m);
    EXPECT_NEAR(signedVolume(m), 8.0 + 1.0, 1e-4);
    EXPECT_EQ(meshBounds(m).min, glm::vec3(-1, -1, -1));
    EXPECT_EQ(meshBounds(m).max, glm::vec3(2, 4, 7));
}

TEST(Primitives, PlacedUnitBoxFillsTheGivenBox) {
    SourceOutput s;
    s.meshes.push_back(makeBox(glm::vec3(1.0f)));
    s.objects.push_back(placeUnitBox(0, {1, -2, 3}, {4, 0, 3.5}));
    const Aabb box = objectBox(s, s.objects[0]);
    EXPECT_EQ(box.min, glm::vec3(1, -2, 3));
    EXPECT_EQ(box.max, glm::vec3(4, 0, 3.5));
    EXPECT_EQ(scaleMatrix({2, 3, 4}) * glm::vec3(1), glm::vec3(2, 3, 4));
}

}  // namespace
}  // namespace occsim
