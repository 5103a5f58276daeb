// The game levels (scenarios/levels/, issue 42) and their generator, scripts/make_levels.py: the
// script makes exactly the committed files, refuses impossible parameters with one line naming
// them (exit 2, nothing written), prints the parameter tables docs/scenario-generators.md shows;
// and each level loads as it claims: named objects sharing meshes, large occluders marked, a
// vehicle moved by its glTF animation, path movers, 16:9 viewports, segments within the run.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "gltf_builder.h"
#include "shell_command.h"
#include "sim/scenario/scenario.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::Outcome;
using testing::shell;
using testing_gltf::TempDir;

const fs::path kRoot = OCCSIM_SOURCE_DIR;
const fs::path kScript = kRoot / "scripts/make_levels.py";
const std::vector<std::string> kLevels = {"courtyards", "interior", "canyon"};

std::string readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

Outcome script(const std::string& arguments) {
    return shell("python3 '" + kScript.string() + "' " + arguments);
}

// Every regular file below `dir`, by its path relative to it.
std::set<std::string> filesBelow(const fs::path& dir) {
    std::set<std::string> out;
    if (!fs::exists(dir)) return out;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (e.is_regular_file()) out.insert(e.path().lexically_relative(dir).generic_string());
    }
    return out;
}

// ---- The script ------------------------------------------------------------------------------

TEST(LevelScript, RegeneratesTheCommittedLevelsByteForByte) {
    TempDir out;
    const Outcome made = script("all --out '" + out.path().string() + "'");
    ASSERT_EQ(made.exit_code, 0) << made.output;
    for (const char* folder : {"levels", "assets/levels"}) {
        const std::set<std::string> made_files = filesBelow(out.path() / folder);
        const std::set<std::string> committed = filesBelow(kRoot / "scenarios" / folder);
        std::set<std::string> committed_made;  // the committed files less the notes beside them
        for (const std::string& f : committed) {
            if (f != "README.md" && f != "SOURCE.txt") committed_made.insert(f);
        }
        EXPECT_EQ(made_files, committed_made) << folder;
        for (const std::string& f : made_files) {
            EXPECT_TRUE(readBytes(out.path() / folder / f) ==
                        readBytes(kRoot / "scenarios" / folder / f))
                << "scenarios/" << folder << "/" << f
                << " is not what scripts/make_levels.py makes; rerun `python3 "
                   "scripts/make_levels.py all`";
        }
    }
}

TEST(LevelScript, SameParametersGiveTheSameBytesAndAnotherSeedAnotherLevel) {
    TempDir a, b, c;
    const std::string level = "courtyards --courtyards 2x2 --cars 4 --people 6 --frames 90 ";
    ASSERT_EQ(script(level + "--out '" + a.path().string() + "'").exit_code, 0);
    ASSERT_EQ(script(level + "--out '" + b.path().string() + "'").exit_code, 0);
    ASSERT_EQ(script(level + "--seed 2 --out '" + c.path().string() + "'").exit_code, 0);
    const std::string file = "assets/levels/courtyards.gltf";
    EXPECT_EQ(readBytes(a.path() / file), readBytes(b.path() / file));
    EXPECT_EQ(readBytes(a.path() / "assets/levels/courtyards.bin"),
              readBytes(b.path() / "assets/levels/courtyards.bin"));
    EXPECT_NE(readBytes(a.path() / file), readBytes(c.path() / file));
}

// Each impossible parameter: exit 2, one line that names the flag and says what was expected,
// and no file written.
TEST(LevelScript, RefusesImpossibleParametersWithOneLineNamingThem) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"courtyards --courtyards 0x3", "--courtyards: expected COLUMNSxROWS"},
        {"courtyards --courtyards 5x5 --door-width 30",
         "--door-width: expected a gate narrower than its wall"},
        {"courtyards --door-width -1", "--door-width: expected a number in (0, 100]"},
        {"courtyards --statues -2", "--statues: expected an integer in [0, 100]"},
        {"courtyards --prop-size 40", "--prop-size: expected a prop smaller than its courtyard"},
        {"courtyards --statues 60", "--statues: 1 trees, 60 statues and 4 benches do not fit"},
        {"courtyards --street-width 5", "--street-width: expected at least 12.8 m"},
        {"courtyards --cars 1000", "--cars: expected at most 48 cars"},
        {"courtyards --seed x", "--seed: expected an integer, got 'x'"},
        // Walls that fill the courtyard or the room: the flags given are named, not the door's
        // (it said "--door-width: ... at most -2 m").
        {"courtyards --courtyard-size 8 --wall-thickness 4",
         "--courtyard-size 8, --wall-thickness 4: expected a courtyard more than 2 m wider inside "
         "than its two walls"},
        {"courtyards --courtyard-size 10 --wall-thickness 4 --door-width 1",
         "--courtyard-size 10, --wall-thickness 4: expected"},
        {"interior --room-size 2x2 --wall-thickness 2", "--room-size: expected rooms at least"},
        {"interior --rooms 1x3", "--rooms: expected at least 2x2"},
        {"interior --door-width 9", "--door-width: expected a door narrower than its wall"},
        {"interior --room-size 3x3", "--room-size: expected rooms at least"},
        {"interior --corridor-width 1", "--corridor-width: expected at least"},
        {"interior --door-height 1.5", "--door-height: expected a door from 2 m"},
        {"interior --furniture 40", "--furniture: 40 pieces do not fit"},
        {"interior --people 100", "--people: expected at most 16 people"},
        {"canyon --street-width 10", "--street-width: expected at least 20.9 m"},
        {"canyon --building-height 30x10", "--building-height: expected MINxMAX with MIN <= MAX"},
        {"canyon --block-size 8x30", "--block-size: expected blocks at least 11.6 m"},
        {"canyon --frames 0", "--frames: expected an integer in [60, 100000]"},
        {"courtyards --bogus 3", "unrecognized arguments: --bogus"},
    };
    for (const auto& [arguments, expected] : cases) {
        TempDir out;
        const Outcome run = script(arguments + " --out '" + out.path().string() + "/made'");
        EXPECT_EQ(run.exit_code, 2) << arguments << ": " << run.output;
        EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1)
            << arguments << ": " << run.output;
        EXPECT_EQ(run.output.rfind("make_levels.py: ", 0), 0u) << arguments << ": " << run.output;
        EXPECT_NE(run.output.find(expected), std::string::npos)
            << arguments << ": expected \"" << expected << "\" in " << run.output;
        EXPECT_FALSE(fs::exists(out.path() / "made")) << arguments << ": wrote files";
    }
    TempDir out;
    fs::create_directories(out.path() / "file");
    std::ofstream(out.path() / "file" / "levels") << "not a folder";
    const Outcome unwritable = script("interior --out '" + (out.path() / "file").string() + "'");
    EXPECT_EQ(unwritable.exit_code, 2) << unwritable.output;
    EXPECT_EQ(std::count(unwritable.output.begin(), unwritable.output.end(), '\n'), 1)
        << unwritable.output;
    EXPECT_NE(unwritable.output.find("--out: expected a folder this user can write"),
              std::string::npos)
        << unwritable.output;
    EXPECT_FALSE(fs::exists(out.path() / "file" / "assets")) << "wrote files";
}

TEST(LevelScript, TheDocsShowTheParameterTablesTheScriptPrints) {
    const Outcome tables = script("--markdown");
    ASSERT_EQ(tables.exit_code, 0) << tables.output;
    ASSERT_GT(tables.output.size(), 500u);
    const std::string page = readBytes(kRoot / "docs/scenario-generators.md");
    EXPECT_NE(page.find(tables.output), std::string::npos)
        << "docs/scenario-generators.md does not hold `python3 scripts/make_levels.py --markdown` "
           "as it prints now:\n"
        << tables.output;
}

// ---- The levels as occsim loads them -----------------------------------------------------------

struct LevelFile {
    Scenario scenario;
    json gltf;
    std::vector<const json*> mesh_nodes;  // in the loader's visit order: depth first, roots first
};

void visit(const json& nodes, int index, std::vector<const json*>& out) {
    const json& node = nodes[index];
    if (node.contains("mesh")) out.push_back(&node);
    for (const json& child : node.value("children", json::array())) visit(nodes, child, out);
}

LevelFile loadLevel(const std::string& name) {
    LevelFile level;
    level.scenario = parseScenarioFile(kRoot / "scenarios/levels" / (name + ".json"));
    std::ifstream in(kRoot / "scenarios/assets/levels" / (name + ".gltf"));
    level.gltf = json::parse(in);
    for (const json& root : level.gltf["scenes"][0]["nodes"]) {
        visit(level.gltf["nodes"], root, level.mesh_nodes);
    }
    return level;
}

TEST(LevelScenarios, EachLoadsItsNamedObjectsSharingMeshesWithTheOccludersMarked) {
    for (const std::string& name : kLevels) {
        SCOPED_TRACE(name);
        const LevelFile level = loadLevel(name);
        const Scene scene = buildScene(level.scenario);
        EXPECT_TRUE(scene.warnings.empty());
        // One object per mesh node, few meshes shared by many of them.
        ASSERT_EQ(scene.objectCount(), level.mesh_nodes.size());
        EXPECT_GT(scene.objectCount(), 150u);
        EXPECT_LT(level.gltf["meshes"].size(), 16u);
        // Every node named, no two alike.
        std::set<std::string> names;
        for (const json& node : level.gltf["nodes"]) {
            const std::string n = node.value("name", "");
            EXPECT_FALSE(n.empty());
            EXPECT_TRUE(names.insert(n).second) << "two nodes named " << n;
        }
        // Heavy props: meshes of hundreds to thousands of triangles (the box of walls aside).
        uint32_t heavy = 0;
        for (const MeshData& mesh : scene.meshes) heavy += mesh.triangleCount() >= 300 ? 1 : 0;
        EXPECT_GE(heavy, 4u);
        // The floor and the walls or buildings are marked as occluders, nothing else is; the
        // scene reads the mark as those objects' role.
        uint32_t occluders = 0;
        bool floor_marked = false;
        ASSERT_EQ(scene.models.size(), 1u);
        ASSERT_EQ(scene.models[0].object_occluder.size(), level.mesh_nodes.size());
        for (uint32_t i = 0; i < level.mesh_nodes.size(); ++i) {
            const json* node = level.mesh_nodes[i];
            const bool marked = node->contains("extras") &&
                                (*node)["extras"].value("occsim_occluder", "") == "always";
            EXPECT_EQ(scene.models[0].object_occluder[i],
                      marked ? OccluderRole::Always : OccluderRole::BySize)
                << (*node)["name"];
            occluders += marked ? 1 : 0;
            if ((*node)["name"] == "floor") floor_marked = marked;
            if (marked) {
                EXPECT_EQ(level.gltf["meshes"][(*node)["mesh"].get<int>()]["name"], "box")
                    << (*node)["name"];
            }
        }
        EXPECT_TRUE(floor_marked);
        EXPECT_GT(occluders, 40u);
    }
}

TEST(LevelScenarios, EachHasAnAnimatedVehiclePathMoversAndSegmentsWithinItsRun) {
    const std::map<std::string, std::string> vehicle = {
        {"courtyards", "truck"}, {"interior", "cart"}, {"canyon", "bus"}};
    for (const std::string& name : kLevels) {
        SCOPED_TRACE(name);
        const LevelFile level = loadLevel(name);
        const Scenario& s = level.scenario;
        const Scene scene = buildScene(s);
        // The vehicle: every object of its group node moved by the playing animation.
        ASSERT_EQ(scene.models.size(), 1u);
        ASSERT_FALSE(scene.models[0].model->animations.empty());
        EXPECT_EQ(scene.models[0].model->animations[0].name, vehicle.at(name) + "_drive");
        EXPECT_TRUE(scene.models[0].playing[0]);
        uint32_t animated = 0;
        for (uint32_t i = 0; i < level.mesh_nodes.size(); ++i) {
            const std::string node = (*level.mesh_nodes[i])["name"];
            const bool of_vehicle = node.rfind(vehicle.at(name) + "/", 0) == 0;
            EXPECT_EQ(static_cast<bool>(scene.models[0].object_animated[i]), of_vehicle) << node;
            animated += of_vehicle ? 1 : 0;
        }
        EXPECT_GE(animated, 1u);
        // The vehicle moves, and so do the path movers.
        uint32_t first = 0;
        while (!scene.models[0].object_animated[first]) ++first;
        WorldState state = initialState(scene);
        const glm::dvec3 before = state.poses[first].position;
        for (int f = 0; f < 30; ++f) stepMovers(scene, state, s.dt_s);
        EXPECT_GT(glm::length(state.poses[first].position - before), 0.5);
        EXPECT_FALSE(s.movers.empty());
        EXPECT_GT(state.moved.size(), animated);
        // The viewports engines use: 16:9.
        EXPECT_EQ(s.width * 9, s.height * 16);
        // Named moments, each inside the run and the camera's path.
        const double run = s.frames * s.dt_s;
        EXPECT_GE(s.frames, 150u);
        EXPECT_LE(s.frames, 300u);
        ASSERT_GE(s.segments.size(), 4u);
        std::set<std::string> segment_names;
        for (const SegmentSpec& seg : s.segments) {
            segment_names.insert(seg.name);
            EXPECT_FALSE(seg.in_frames);
            EXPECT_GE(seg.from_s, 0.0) << seg.name;
            EXPECT_LT(seg.from_s, seg.to_s) << seg.name;
            EXPECT_LE(seg.to_s, run) << seg.name;
            EXPECT_LE(seg.to_s, s.camera.keyframes.back().time_s + 1.0) << seg.name;
        }
        EXPECT_TRUE(segment_names.count(vehicle.at(name)));
        EXPECT_TRUE(segment_names.count(name == "interior" ? "door-1-1-e" : "corner"));
    }
    // One of them at 1280x720.
    EXPECT_EQ(loadLevel("courtyards").scenario.width, 1280u);
    EXPECT_EQ(loadLevel("courtyards").scenario.height, 720u);
}

}  // namespace
}  // namespace occsim
