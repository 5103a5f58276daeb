// Shared by the objects database's tests: a small glTF level with named nodes and a mover that
// async misses, frames.csv read back, and objects.sqlite queried.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "gltf_builder.h"
#include "shell_command.h"
#include "sim/record/sqlite.h"

namespace occsim::testing {

using testing_gltf::GltfBuilder;
using testing_gltf::json;
using testing_gltf::TempDir;

inline std::string fileText(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A closed unit cube (-0.5 .. 0.5), counter-clockwise seen from outside.
inline int unitCube(GltfBuilder& b) {
    const int p = b.vec3({{-.5f, -.5f, -.5f},
                          {.5f, -.5f, -.5f},
                          {.5f, .5f, -.5f},
                          {-.5f, .5f, -.5f},
                          {-.5f, -.5f, .5f},
                          {.5f, -.5f, .5f},
                          {.5f, .5f, .5f},
                          {-.5f, .5f, .5f}});
    const int i = b.indices({0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 4, 7, 0, 7, 3,
                             1, 2, 6, 1, 6, 5, 0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2});
    return b.mesh("Cube", json::array({GltfBuilder::primitive(p, i)}));
}

// A walled yard: a wall 8 m wide and 4 m tall across the view at z = -2, three crates behind it
// (z = -8, hidden), two lamps beside it (seen), and a truck behind the wall (z = -6) that a glTF
// animation drives out to the right between 0.4 s and 0.9 s, into view (then it holds). The camera
// stands still at eye height 8 m in front of the wall. Returns the scenario file.
inline std::filesystem::path writeWalledYard(const TempDir& dir, uint32_t frames = 40) {
    GltfBuilder b;
    const int cube = unitCube(b);
    b.node({{"name", "wall"}, {"mesh", cube}, {"translation", {0, 2, -2}}, {"scale", {8, 4, 0.5}}});
    for (int i = 0; i < 3; ++i) {
        b.node({{"name", "crate." + std::to_string(i)},
                {"mesh", cube},
                {"translation", {-2.0 + 2.0 * i, 0.5, -8}}});
    }
    b.node({{"name", "lamp.left"},
            {"mesh", cube},
            {"translation", {-7, 1, -4}},
            {"scale", {0.5, 2, 0.5}}});
    b.node({{"name", "lamp.right"},
            {"mesh", cube},
            {"translation", {7, 1, -4}},
            {"scale", {0.5, 2, 0.5}}});
    const int truck = b.node({{"name", "truck"},
                              {"mesh", cube},
                              {"translation", {0, 0.75, -6}},
                              {"scale", {2, 1.5, 1}}});
    b.animation("Drive", {{truck,
                           "translation",
                           "LINEAR",
                           {0.0f, 0.4f, 0.9f},
                           {0, 0.75f, -6, 0, 0.75f, -6, 8, 0.75f, -6}}});
    dir.write("yard.gltf", b.text());
    const json scenario = {
        {"format_version", 1},
        {"name", "walled-yard"},
        {"seed", 3},
        {"frames", frames},
        {"dt", 1.0 / 30.0},
        {"warmup_frames", 2},
        {"viewport", {{"width", 160}, {"height", 120}}},
        {"camera",
         {{"near", 0.1},
          {"far", 100},
          {"keyframes", {{{"time", 0}, {"position", {0, 1.5, 8}}, {"target", {0, 1.5, -20}}}}}}},
        {"scene",
         {{"sources",
           {{{"type", "gltf"}, {"path", "yard.gltf"}, {"animation", {{"mode", "clamp"}}}}}}}},
        {"culling", {{"algorithm", "async"}}},
        {"bsp", {{"max_objects_per_leaf", 1}}}};
    return dir.write("yard.json", scenario.dump());
}

// frames.csv as rows of named columns.
struct FramesCsv {
    std::vector<std::map<std::string, std::string>> rows;

    explicit FramesCsv(const std::filesystem::path& file) {
        std::istringstream in(fileText(file));
        std::string line;
        std::vector<std::string> header;
        while (std::getline(in, line)) {
            std::vector<std::string> cells;
            std::stringstream cs(line);
            std::string cell;
            while (std::getline(cs, cell, ',')) cells.push_back(cell);
            if (header.empty()) {
                header = cells;
                continue;
            }
            std::map<std::string, std::string> row;
            for (size_t i = 0; i < header.size() && i < cells.size(); ++i)
                row[header[i]] = cells[i];
            rows.push_back(row);
        }
    }
};

// One integer from a query with parameters bound in order.
inline int64_t queryInteger(sql::Database& db, const std::string& query,
                            const std::vector<std::string>& texts = {},
                            const std::vector<int64_t>& numbers = {}) {
    sql::Statement s = db.prepare(query);
    int i = 1;
    for (const std::string& t : texts) s.bind(i++, std::string_view(t));
    for (int64_t n : numbers) s.bind(i++, n);
    return s.step() ? s.integer(0) : -1;
}

}  // namespace occsim::testing
