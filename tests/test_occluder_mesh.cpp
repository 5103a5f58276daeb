// Inscribed occluder meshes (sim/scene/occluder_mesh.h): the checks they rest on, and the
// property that matters, against the exact raster of the object (every pixel centre, in double):
// from eyes outside the object, the occluder covers no pixel the object does not, and lies behind
// it where both do. Over every mesh the repository's scenes are built from and random ones.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "occsim/culling/testing/triangle_raster_device.h"
#include "sim/scene/gltf_source.h"
#include "sim/scene/occluder_mesh.h"
#include "sim/scene/primitives.h"
#include "sim/scene/teapot.h"

namespace occsim {
namespace {

const std::filesystem::path kAssets = std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/assets";

// A closed, star-shaped, bumpy ball: a sphere whose radius varies with direction.
MeshData bumpyBall(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    MeshData m = makeSphere(1.0f, 16 + seed % 16, 10 + seed % 10);
    const double a = 0.1 + 0.3 * u(rng), b = 0.1 + 0.3 * u(rng);
    const double fa = 2 + std::floor(u(rng) * 4), fb = 1 + std::floor(u(rng) * 4);
    const glm::dvec3 stretch(0.5 + u(rng) * 2, 0.5 + u(rng) * 2, 0.5 + u(rng) * 2);
    for (glm::vec3& p : m.positions) {
        const glm::dvec3 d = glm::normalize(glm::dvec3(p) - glm::dvec3(0, 1, 0));  // its centre
        const double r = 1.0 + a * std::sin(fa * d.x + 1.3 * d.z) + b * std::cos(fb * 3 * d.y);
        p = glm::vec3(d * r * stretch);
    }
    return m;
}

// Every pixel the occluder covers, the object covers, at least as near; from `views` eyes
// around the object, outside its box. Returns the pixels the occluder covered.
uint64_t checkInscribed(const MeshData& object, const MeshData& occluder, uint32_t views,
                        uint32_t seed, const std::string& what) {
    std::vector<glm::vec3> positions = object.positions;
    positions.insert(positions.end(), occluder.positions.begin(), occluder.positions.end());
    // Indices stay relative to each mesh's first vertex (MeshRange).
    std::vector<uint32_t> indices = object.indices;
    indices.insert(indices.end(), occluder.indices.begin(), occluder.indices.end());
    const std::vector<MeshRange> ranges = {{0, static_cast<uint32_t>(object.indices.size()), 0,
                                            static_cast<uint32_t>(object.positions.size())},
                                           {static_cast<uint32_t>(object.indices.size()),
                                            static_cast<uint32_t>(occluder.indices.size()),
                                            static_cast<uint32_t>(object.positions.size()),
                                            static_cast<uint32_t>(occluder.positions.size())}};
    const std::vector<uint32_t> object_mesh = {0, 1};
    const Aabb box = meshBounds(object);
    const glm::dvec3 centre = glm::dvec3(box.min + box.max) * 0.5;
    const double size = glm::length(glm::dvec3(box.max - box.min));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    uint64_t covered = 0;
    for (uint32_t v = 0; v < views; ++v) {
        glm::dvec3 dir(u(rng), u(rng), u(rng));
        if (glm::length(dir) < 1e-3) dir = glm::dvec3(1, 0, 0);
        dir = glm::normalize(dir);
        // From just outside the box (half a diagonal plus a little) to three diagonals away.
        const double distance = size * (0.52 + 1.5 * (u(rng) + 1.0));
        const glm::dvec3 eye = centre + dir * distance;
        const glm::dvec3 up = std::abs(dir.y) > 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        const uint32_t width = 96 + v % 64, height = 72 + v % 48;
        const glm::dmat4 vp =
            glm::perspective(glm::radians(50.0 + 30.0 * (v % 3)),
                             static_cast<double>(width) / height, 0.01 * size, 100.0 * size) *
            glm::lookAt(eye, centre + glm::dvec3(u(rng), u(rng), u(rng)) * 0.2 * size, up);
        const std::vector<glm::mat4> transforms = {glm::mat4(1.0f), glm::mat4(1.0f)};
        const CullMeshes meshes{positions, indices, ranges, object_mesh, transforms, {}, {}};
        TriangleRasterDevice object_raster(width, height), occluder_raster(width, height);
        object_raster.beginFrame(glm::mat4(vp), meshes);
        occluder_raster.beginFrame(glm::mat4(vp), meshes);
        object_raster.drawObject(0);
        occluder_raster.drawObject(1);
        const std::vector<double>& s = object_raster.depth();
        const std::vector<double>& o = occluder_raster.depth();
        for (size_t i = 0; i < o.size(); ++i) {
            if (o[i] <= 0.0) continue;
            ++covered;
            // 1/w: larger is nearer. The object must be there, and not behind the occluder.
            if (!(s[i] > 0.0 && s[i] >= o[i])) {
                ADD_FAILURE() << what << ": view " << v << " pixel " << i % width << ","
                              << i / width << ": occluder 1/w " << o[i] << ", object " << s[i];
                return covered;
            }
        }
    }
    return covered;
}

// The Utah teapot is open (its lid sits in the body's opening with a gap around it, the spout's
// tip is open, the handle and spout end inside the body): there is no solid to be inside of, so
// it gets no occluder mesh and occludes with its own.
TEST(OccluderMesh, TheTeapotIsOpenAndKeepsItsOwnMesh) {
    const OccluderMesh made = makeInscribedOccluder(tessellateTeapot(4));
    EXPECT_NE(made.refusal.find("not closed"), std::string::npos) << made.refusal;
    EXPECT_EQ(made.mesh.triangleCount(), 0u);
}

TEST(OccluderMesh, ASphereGetsAnInscribedOccluderWithAFractionOfItsTriangles) {
    const MeshData sphere = makeSphere(1.0f, 32, 24);
    const OccluderMesh made = makeInscribedOccluder(sphere);
    ASSERT_EQ(made.refusal, "");
    EXPECT_GT(made.mesh.triangleCount(), 0u);
    EXPECT_LT(made.mesh.triangleCount(), sphere.triangleCount() / 4);
    EXPECT_GT(made.kept_area_share, 0.9);
    EXPECT_GT(checkInscribed(sphere, made.mesh, 60, 1, "sphere"), 10000u);
}

TEST(OccluderMesh, EveryMeshOfTheRepositorysScenesIsInscribedOrRefusedWithAReason) {
    std::vector<std::pair<std::string, MeshData>> meshes;
    for (const uint32_t level : {2u, 4u, 6u}) {
        meshes.emplace_back("teapot level " + std::to_string(level), tessellateTeapot(level));
    }
    meshes.emplace_back("box", makeBox({1, 2, 3}));
    meshes.emplace_back("cylinder", makeCylinder(0.5f, 2.0f, 24));
    meshes.emplace_back("sphere", makeSphere(1.0f, 24, 16));
    for (const auto& entry : std::filesystem::recursive_directory_iterator(kAssets)) {
        const std::string ext = entry.path().extension().string();
        if (ext != ".gltf" && ext != ".glb") continue;
        GltfSourceSpec spec;
        spec.path = entry.path();
        const SourceOutput out = loadGltfSource(spec, 1);
        for (size_t m = 0; m < out.meshes.size(); ++m) {
            meshes.emplace_back(entry.path().filename().string() + " mesh " + std::to_string(m),
                                out.meshes[m]);
        }
    }
    uint32_t made = 0;
    for (const auto& [name, mesh] : meshes) {
        const OccluderMesh o = makeInscribedOccluder(mesh);
        if (!o.refusal.empty()) {
            EXPECT_EQ(o.mesh.triangleCount(), 0u) << name;
            EXPECT_EQ(o.refusal.find('\n'), std::string::npos) << name;
            continue;
        }
        ++made;
        EXPECT_LT(o.mesh.triangleCount(), mesh.triangleCount()) << name;
        checkInscribed(mesh, o.mesh, 12, made, name);
    }
    EXPECT_GE(made, 4u);  // the teapots, the cylinder and the sphere at least
}

TEST(OccluderMesh, RandomClosedMeshesGetInscribedOccluders) {
    uint32_t made = 0;
    for (uint32_t seed = 1; seed <= 12; ++seed) {
        const MeshData ball = bumpyBall(seed);
        const OccluderMesh o = makeInscribedOccluder(ball);
        if (!o.refusal.empty()) continue;
        ++made;
        checkInscribed(ball, o.mesh, 16, seed, "ball " + std::to_string(seed));
    }
    EXPECT_GE(made, 10u);
}

// A mesh someone made keeps only its triangles inside the object: a box half as large inside a
// sphere is kept whole; one that reaches out of it keeps what lies inside, and those cover no
// pixel the sphere does not; one wholly outside, or any against an open mesh, is refused.
TEST(OccluderMesh, AnAuthoredOccluderKeepsOnlyWhatLiesInsideItsObject) {
    const MeshData sphere = makeSphere(1.0f, 32, 24);
    const glm::vec3 centre = (meshBounds(sphere).min + meshBounds(sphere).max) * 0.5f;
    auto boxAt = [&](glm::vec3 size, glm::vec3 offset) {
        MeshData box = makeBox(size);
        const glm::vec3 mid = (meshBounds(box).min + meshBounds(box).max) * 0.5f;
        for (glm::vec3& p : box.positions) p += centre + offset - mid;
        return box;
    };
    const OccluderMesh inside = checkAuthoredOccluder(sphere, boxAt({1, 1, 1}, {0, 0, 0}));
    ASSERT_EQ(inside.refusal, "");
    EXPECT_EQ(inside.mesh.triangleCount(), 12u);
    EXPECT_EQ(inside.dropped_triangles, 0u);
    EXPECT_GT(checkInscribed(sphere, inside.mesh, 40, 2, "box in sphere"), 1000u);

    MeshData ball = makeSphere(0.6f, 16, 12);  // half out of the sphere
    const glm::vec3 ball_mid = (meshBounds(ball).min + meshBounds(ball).max) * 0.5f;
    for (glm::vec3& p : ball.positions) p += centre + glm::vec3(0.7f, 0, 0) - ball_mid;
    const OccluderMesh partly = checkAuthoredOccluder(sphere, ball);
    ASSERT_EQ(partly.refusal, "");
    EXPECT_GT(partly.dropped_triangles, ball.triangleCount() / 4);
    EXPECT_GT(partly.mesh.triangleCount(), ball.triangleCount() / 4);
    checkInscribed(sphere, partly.mesh, 40, 3, "ball half out of the sphere");

    const OccluderMesh outside = checkAuthoredOccluder(sphere, boxAt({1, 1, 1}, {3, 0, 0}));
    EXPECT_NE(outside.refusal.find("none of its 12 triangles lies inside its object"),
              std::string::npos)
        << outside.refusal;
    EXPECT_EQ(outside.mesh.triangleCount(), 0u);

    MeshData quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.normals.assign(4, {0, 0, 1});
    quad.indices = {0, 1, 2, 0, 2, 3};
    const OccluderMesh open = checkAuthoredOccluder(quad, boxAt({0.1f, 0.1f, 0.1f}, {0, 0, 0}));
    EXPECT_NE(open.refusal.find("encloses no solid to check it against"), std::string::npos)
        << open.refusal;
}

TEST(OccluderMesh, AnOpenOrTinyMeshIsRefused) {
    MeshData quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.normals.assign(4, {0, 0, 1});
    quad.indices = {0, 1, 2, 0, 2, 3};
    OccluderMeshSettings settings;
    settings.min_triangles = 1;
    EXPECT_NE(makeInscribedOccluder(quad, settings).refusal.find("not closed"), std::string::npos);
    EXPECT_NE(makeInscribedOccluder(makeBox({1, 1, 1})).refusal.find("too few"), std::string::npos);
    // A sphere with one triangle turned over is not consistently oriented.
    MeshData flipped = makeSphere(1.0f, 12, 8);
    std::swap(flipped.indices[30], flipped.indices[31]);
    EXPECT_NE(makeInscribedOccluder(flipped).refusal, "");
}

TEST(OccluderMesh, ThePointInsideTestCountsCrossings) {
    const MeshData box = makeBox({2, 2, 2});  // from y = 0 to 2 (the box sits on the ground)
    std::vector<glm::dvec3> p;
    std::vector<uint32_t> remap;
    for (const glm::vec3& v : box.positions) {  // its faces repeat positions exactly
        size_t k = 0;
        while (k < p.size() && p[k] != glm::dvec3(v)) ++k;
        if (k == p.size()) p.emplace_back(v);
        remap.push_back(static_cast<uint32_t>(k));
    }
    std::vector<uint32_t> idx;
    for (const uint32_t i : box.indices) idx.push_back(remap[i]);
    const Aabb b = meshBounds(box);
    const glm::dvec3 c = glm::dvec3(b.min + b.max) * 0.5;
    EXPECT_TRUE(pointInsideClosedMesh(c, p, idx));
    EXPECT_TRUE(pointInsideClosedMesh(c + glm::dvec3(0.5, 0.3, -0.2), p, idx));
    EXPECT_FALSE(pointInsideClosedMesh(c + glm::dvec3(1.5, 0, 0), p, idx));
    EXPECT_FALSE(pointInsideClosedMesh(c + glm::dvec3(0, 0, -3), p, idx));
}

TEST(OccluderMesh, TrianglesWithinTheGapCountAsMeeting) {
    const glm::dvec3 a[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const glm::dvec3 crossing[3] = {{0.2, 0.2, -1}, {0.2, 0.2, 1}, {0.3, 0.25, 0}};
    const glm::dvec3 above[3] = {{0, 0, 0.01}, {1, 0, 0.01}, {0, 1, 0.01}};
    const glm::dvec3 beside[3] = {{0.6, 0.6, 0}, {2, 0.6, 0}, {0.6, 2, 0}};  // coplanar, apart
    EXPECT_TRUE(trianglesWithinGap(a, crossing, 0.0));
    EXPECT_FALSE(trianglesWithinGap(a, above, 0.001));
    EXPECT_TRUE(trianglesWithinGap(a, above, 0.02));
    EXPECT_FALSE(trianglesWithinGap(a, beside, 0.01));
    EXPECT_TRUE(trianglesWithinGap(a, beside, 0.2));
}

}  // namespace
}  // namespace occsim
