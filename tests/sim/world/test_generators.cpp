// The procedural scene generators (city, library, plant): deterministic per seed, scaling with
// their spec, valid closed meshes with outward faces, lanes that keep movers out of the geometry,
// and everything inside the source's region. The primitives they are built from:
// tests/sim/scene/test_primitives.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <tuple>

#include "mesh_checks.h"
#include "sim/scenario/scenario.h"
#include "sim/scene/generators.h"
#include "sim/scene/primitives.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

// The repository (OCCSIM_SOURCE_DIR, as every test folder's executable is given it).
const std::filesystem::path kRepo = OCCSIM_SOURCE_DIR;
const std::filesystem::path kSmall = kRepo / "scenarios/small";
const std::filesystem::path kPaper = kRepo / "scenarios/paper";

using testing::expectFaceNormalsAgree;
using testing::expectValidMesh;
using testing::isClosed;
using testing::objectBox;
using testing::signedVolume;

// --- Source checks -------------------------------------------------------------------------

void expectSameOutput(const SourceOutput& a, const SourceOutput& b) {
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
        EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
    }
    ASSERT_EQ(a.objects.size(), b.objects.size());
    for (size_t i = 0; i < a.objects.size(); ++i) {
        EXPECT_EQ(a.objects[i].mesh, b.objects[i].mesh);
        EXPECT_EQ(a.objects[i].position, b.objects[i].position);
        EXPECT_EQ(a.objects[i].linear, b.objects[i].linear);
    }
    EXPECT_EQ(a.lanes, b.lanes);
    EXPECT_EQ(a.region.min, b.region.min);
    EXPECT_EQ(a.region.max, b.region.max);
}

bool samePlacement(const SourceOutput& a, const SourceOutput& b) {
    if (a.objects.size() != b.objects.size()) return false;
    for (size_t i = 0; i < a.objects.size(); ++i) {
        if (a.objects[i].position != b.objects[i].position ||
            a.objects[i].linear != b.objects[i].linear) {
            return false;
        }
    }
    return true;
}

uint64_t triangles(const SourceOutput& s) {
    uint64_t n = 0;
    for (const PlacedObject& o : s.objects) n += s.meshes[o.mesh].triangleCount();
    return n;
}

void expectValidSource(const SourceOutput& s) {
    ASSERT_FALSE(s.objects.empty());
    for (size_t i = 0; i < s.meshes.size(); ++i)
        expectValidMesh(s.meshes[i], "mesh " + std::to_string(i));
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const PlacedObject& o = s.objects[i];
        ASSERT_LT(o.mesh, s.meshes.size());
        // A positive determinant keeps the meshes' outward faces outward once placed.
        EXPECT_GT(glm::determinant(o.linear), 0.0f) << "object " << i;
    }
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

// Every object's world box lies within the source's region (to float rounding).
void expectWithinRegion(const SourceOutput& s) {
    ASSERT_FALSE(isEmpty(s.region));
    const glm::vec3 slack(1e-3f);
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const Aabb box = objectBox(s, s.objects[i]);
        EXPECT_TRUE(
            contains(Aabb{glm::vec3(s.region.min) - slack, glm::vec3(s.region.max) + slack}, box))
            << "object " << i;
    }
}

// Two boxes at least half a millimetre apart on some axis: neither touching nor overlapping.
bool apart(const Aabb& a, const Aabb& b) {
    for (int axis = 0; axis < 3; ++axis) {
        if (a.max[axis] + 5e-4f < b.min[axis] || b.max[axis] + 5e-4f < a.min[axis]) return true;
    }
    return false;
}

// No two objects touch (all of these sources' objects are boxes or fill their boxes closely):
// along a contact line depths tie, and draw order, not culling, would decide those pixels.
void expectNothingTouches(const SourceOutput& s) {
    std::vector<Aabb> boxes;
    for (const PlacedObject& o : s.objects) boxes.push_back(objectBox(s, o));
    for (size_t i = 0; i < boxes.size(); ++i) {
        for (size_t j = i + 1; j < boxes.size(); ++j) {
            ASSERT_TRUE(apart(boxes[i], boxes[j])) << "objects " << i << " and " << j;
        }
    }
}

// Samples each lane every 0.25 m and checks the room a mover needs above each sample (from 5 cm
// to `clearance` above the lane point, where a mover's base rests) is inside no object's box.
void expectLanesClear(const SourceOutput& s, double clearance) {
    ASSERT_FALSE(s.lanes.empty());
    std::vector<Aabb> boxes;
    for (const PlacedObject& o : s.objects) boxes.push_back(objectBox(s, o));
    size_t samples = 0;
    for (size_t l = 0; l < s.lanes.size(); ++l) {
        const auto& lane = s.lanes[l];
        ASSERT_GE(lane.size(), 3u) << "lane " << l << " is not a loop";
        for (size_t p = 0; p < lane.size(); ++p) {
            const glm::dvec3 a = lane[p], b = lane[(p + 1) % lane.size()];
            const int steps = std::max(1, static_cast<int>(glm::length(b - a) / 0.25));
            for (int k = 0; k < steps; ++k) {
                const glm::dvec3 at = a + (b - a) * (static_cast<double>(k) / steps);
                for (double h = 0.05; h <= clearance + 1e-9; h += 0.25) {
                    const glm::vec3 q(at + glm::dvec3(0, h, 0));
                    for (size_t o = 0; o < boxes.size(); ++o) {
                        const Aabb& box = boxes[o];
                        const bool inside = q.x > box.min.x && q.x < box.max.x && q.y > box.min.y &&
                                            q.y < box.max.y && q.z > box.min.z && q.z < box.max.z;
                        ASSERT_FALSE(inside) << "lane " << l << " at (" << q.x << ", " << q.y
                                             << ", " << q.z << ") is inside object " << o;
                    }
                    ++samples;
                }
            }
        }
    }
    EXPECT_GT(samples, 100u);
}

CitySpec smallCity() {
    CitySpec c;
    c.blocks_x = 3;
    c.blocks_z = 2;
    c.buildings_per_block = 5;
    return c;
}

LibrarySpec smallLibrary() {
    LibrarySpec l;
    l.rows = 3;
    l.shelves_per_row = 2;
    l.levels = 3;
    l.books_per_level = 12;
    return l;
}

PlantSpec smallPlant() {
    PlantSpec p;
    p.units_x = 2;
    p.units_z = 2;
    p.floors = 2;
    p.pipes_per_unit = 12;
    p.tanks_per_unit = 4;
    return p;
}

// --- The three generators, one test per property ---------------------------------------------

struct Generator {
    const char* name;
    std::function<SourceOutput(uint64_t)> make;
};

const Generator kGenerators[] = {
    {"city", [](uint64_t seed) { return generateCity(smallCity(), seed); }},
    {"library", [](uint64_t seed) { return generateLibrary(smallLibrary(), seed); }},
    {"plant", [](uint64_t seed) { return generatePlant(smallPlant(), seed); }},
};

TEST(Generators, AreDeterministicPerSeedAndDifferAcrossSeeds) {
    for (const Generator& g : kGenerators) {
        SCOPED_TRACE(g.name);
        const SourceOutput a = g.make(5), b = g.make(5), c = g.make(6);
        expectSameOutput(a, b);
        EXPECT_FALSE(samePlacement(a, c));
    }
}

TEST(Generators, MeshesAreValidClosedAndOutward) {
    for (const Generator& g : kGenerators) {
        SCOPED_TRACE(g.name);
        expectValidSource(g.make(1));
    }
}

TEST(Generators, EveryObjectLiesWithinTheRegion) {
    for (const Generator& g : kGenerators) {
        SCOPED_TRACE(g.name);
        for (uint64_t seed : {1u, 2u, 3u}) expectWithinRegion(g.make(seed));
    }
}

// Objects share meshes (instancing through `linear`), yet each costs enough triangles that a
// culler gains something by not drawing it.
// (The city at its default size: its buildings share one mesh per archetype, and a handful of
// blocks has too few buildings for archetypes to repeat much.)
TEST(Generators, ShareMeshesAcrossObjectsAndGiveThemDetail) {
    for (const SourceOutput& s : {generateCity(CitySpec{}, 1), generateLibrary(smallLibrary(), 1),
                                  generatePlant(smallPlant(), 1)}) {
        EXPECT_LT(s.meshes.size() * 3, s.objects.size());
        EXPECT_GT(triangles(s), 20 * s.objects.size());
    }
}

// --- City ------------------------------------------------------------------------------------

TEST(City, MoreBlocksAndBuildingsPerBlockMakeMoreObjects) {
    CitySpec spec = smallCity();
    const size_t base = generateCity(spec, 1).objects.size();
    spec.blocks_x = 6;
    const size_t wider = generateCity(spec, 1).objects.size();
    spec.buildings_per_block = 10;
    const size_t denser = generateCity(spec, 1).objects.size();
    EXPECT_GT(wider, base + 10);
    EXPECT_GT(denser, wider + 10);
}

TEST(City, BuildingHeightsStayInTheRangeAndVary) {
    CitySpec spec = smallCity();
    spec.height_min_m = 10;
    spec.height_max_m = 50;
    const SourceOutput s = generateCity(spec, 3);
    std::set<float> tops;
    size_t buildings = 0;
    for (const PlacedObject& o : s.objects) {
        if (o.mesh == 0) continue;  // streets and pavements share the unit box
        ++buildings;
        const Aabb box = objectBox(s, o);
        // The roof line is the building's height; parapet, roof housing and mast stand above it.
        EXPECT_GE(box.max.y, 10.0f);
        EXPECT_LE(box.max.y, 50.0f + 10.5f);
        EXPECT_GT(box.min.y, 0.0f) << "buildings stand on the pavement, above the street";
        tops.insert(box.max.y);
    }
    EXPECT_GE(buildings, 3u * 2u * 3u);
    EXPECT_GT(tops.size(), buildings / 2);
}

TEST(City, NoTwoObjectsTouch) {
    for (uint64_t seed : {1u, 2u}) expectNothingTouches(generateCity(smallCity(), seed));
    CitySpec crowded = smallCity();
    crowded.block_size_m = 20;
    crowded.buildings_per_block = 12;
    expectNothingTouches(generateCity(crowded, 3));
}

TEST(City, CarLanesStayOnTheStreets) {
    for (uint64_t seed : {1u, 9u}) expectLanesClear(generateCity(smallCity(), seed), 2.5);
    expectLanesClear(generateCity(CitySpec{}, 4), 2.5);
}

TEST(City, OneRingRoadPerRowAndColumnOfBlocks) {
    const CitySpec spec = smallCity();
    const SourceOutput s = generateCity(spec, 1);
    EXPECT_EQ(s.lanes.size(), spec.blocks_x + spec.blocks_z);
}

// --- Library ---------------------------------------------------------------------------------

TEST(Library, HoldsExactlyTheBooksAskedFor) {
    const LibrarySpec spec = smallLibrary();
    const SourceOutput s = generateLibrary(spec, 1);
    // Floor, four walls, sides (one more than units per row), boards (levels + top) and books.
    const size_t sides = spec.rows * (spec.shelves_per_row + 1);
    const size_t boards = spec.rows * spec.shelves_per_row * (spec.levels + 1);
    const size_t books = spec.rows * spec.shelves_per_row * spec.levels * spec.books_per_level;
    EXPECT_EQ(s.objects.size(), 5 + sides + boards + books);
    LibrarySpec more = spec;
    more.books_per_level *= 2;
    EXPECT_EQ(generateLibrary(more, 1).objects.size(), 5 + sides + boards + 2 * books);
}

TEST(Library, BooksHaveAFewDozenTriangles) {
    const SourceOutput s = generateLibrary(smallLibrary(), 2);
    size_t books = 0;
    for (const PlacedObject& o : s.objects) {
        if (o.mesh == 0) continue;  // floor, walls, sides and boards share the unit box
        EXPECT_GE(s.meshes[o.mesh].triangleCount(), 36u);
        EXPECT_LE(s.meshes[o.mesh].triangleCount(), 120u);
        ++books;
    }
    EXPECT_EQ(books, 3u * 2u * 3u * 12u);
}

TEST(Library, NoTwoObjectsTouch) {
    for (uint64_t seed : {1u, 2u}) expectNothingTouches(generateLibrary(smallLibrary(), seed));
    LibrarySpec packed = smallLibrary();
    packed.books_per_level = 40;
    expectNothingTouches(generateLibrary(packed, 3));
}

TEST(Library, PeopleLanesRunThroughTheAislesClearOfShelvesAndBooks) {
    for (uint64_t seed : {1u, 7u}) expectLanesClear(generateLibrary(smallLibrary(), seed), 2.0);
    LibrarySpec narrow = smallLibrary();
    narrow.aisle_width_m = 1.0;
    expectLanesClear(generateLibrary(narrow, 3), 2.0);
}

// --- Plant -----------------------------------------------------------------------------------

TEST(Plant, MoreUnitsFloorsAndPipesMakeMoreObjects) {
    PlantSpec spec = smallPlant();
    const size_t base = generatePlant(spec, 1).objects.size();
    spec.units_x = 4;
    const size_t wider = generatePlant(spec, 1).objects.size();
    spec.floors = 4;
    const size_t taller = generatePlant(spec, 1).objects.size();
    spec.pipes_per_unit = 40;
    const size_t piped = generatePlant(spec, 1).objects.size();
    EXPECT_GT(wider, base * 3 / 2);
    EXPECT_GT(taller, wider * 3 / 2);
    EXPECT_GT(piped, taller + 4 * 2 * 20);
}

TEST(Plant, WalkwayAndFlierLanesAreClear) {
    for (uint64_t seed : {1u, 5u}) expectLanesClear(generatePlant(smallPlant(), seed), 2.0);
    PlantSpec squat = smallPlant();
    squat.floor_height_m = 4.0;  // too low for pipes across the corridor: they run along it
    squat.unit_size_m = 12.0;
    expectLanesClear(generatePlant(squat, 2), 2.0);
}

TEST(Plant, TooManyTanksOrPipesAreLeftOutWithAWarning) {
    PlantSpec spec = smallPlant();
    spec.tanks_per_unit = 9;  // six side bays: 3 too many in each of the 4 units
    spec.pipes_per_unit = 400;
    const SourceOutput s = generatePlant(spec, 1);
    ASSERT_EQ(s.warnings.size(), 2u);
    EXPECT_NE(s.warnings[0].find("12 tanks left out"), std::string::npos) << s.warnings[0];
    EXPECT_NE(s.warnings[1].find("pipes left out"), std::string::npos) << s.warnings[1];
}

TEST(Plant, PipesBeamsAndColumnsTouchNothing) {
    const SourceOutput s = generatePlant(smallPlant(), 4);
    std::vector<Aabb> boxes;
    for (const PlacedObject& o : s.objects) boxes.push_back(objectBox(s, o));
    const auto isPipe = [&](const PlacedObject& o) {
        return s.meshes[o.mesh].triangleCount() == 4 * 16;
    };
    const auto isGirder = [&](const PlacedObject& o) { return o.mesh == s.objects[0].mesh + 1; };
    const auto isUpright = [](const PlacedObject& o) { return o.linear[1].y != 0.0f; };
    size_t pipes = 0, checked = 0;
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const PlacedObject& a = s.objects[i];
        pipes += isPipe(a);
        // Pipes and beams against everything; columns against columns (floor slabs are notched
        // round the columns, and tank legs reach up under their sphere, so their boxes overlap).
        const bool against_all = isPipe(a) || (isGirder(a) && !isUpright(a));
        for (size_t j = 0; j < s.objects.size(); ++j) {
            const PlacedObject& b = s.objects[j];
            const bool columns = isGirder(a) && isUpright(a) && isGirder(b) && isUpright(b);
            if (i == j || !(against_all || columns)) continue;
            ASSERT_TRUE(apart(boxes[i], boxes[j])) << "objects " << i << " and " << j;
            ++checked;
        }
    }
    EXPECT_EQ(pipes, 2u * 2u * 12u);
    EXPECT_GT(checked, 1000u);
}

// --- Through the scenario files -------------------------------------------------------------

TEST(GeneratorScenarios, SmallAndPaperScenariosBuildWithMoversOnTheLanes) {
    for (const auto& dir : {kSmall, kPaper}) {
        for (const char* name : {"city", "library", "plant"}) {
            const std::filesystem::path file =
                dir / (std::string(name) + (dir == kSmall ? "-small.json" : ".json"));
            SCOPED_TRACE(file.string());
            const Scenario scenario = parseScenarioFile(file);
            const Scene scene = buildScene(scenario);
            EXPECT_GT(scene.objectCount(), 50u);
            EXPECT_FALSE(scene.paths.empty());
            EXPECT_FALSE(scene.initial_movers.empty());
            EXPECT_TRUE(scene.warnings.empty());
        }
    }
}

TEST(GeneratorScenarios, PlantFloorHeightIsReadAndRangeChecked) {
    const std::string text = R"({"format_version": 1,
        "camera": {"keyframes": [{"time": 0, "position": [0, 2, 0], "target": [1, 2, 0]}]},
        "scene": {"sources": [{"type": "plant", "floor_height": 4.5}]}})";
    const Scenario s = parseScenarioText(text, "plant.json");
    EXPECT_DOUBLE_EQ(std::get<PlantSpec>(s.sources.at(0).spec).floor_height_m, 4.5);
    std::string bad = text;
    bad.replace(bad.find("4.5"), 3, "1.0");
    EXPECT_THROW(parseScenarioText(bad, "plant.json"), ScenarioError);
}

}  // namespace
}  // namespace occsim
