// What each scene source is asked to build, as plain data: the scenario parser fills these and
// the scene layer (sim/scene/) builds from them. Units: metres, degrees.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "occsim/culling/geometry/aabb.h"

namespace occsim {

// A box in world coordinates, in double like the camera and every pose: a region 10^12 m out is
// where the scenario puts it (in float it would land kilometres away from the camera aimed at
// it). Empty (min > max) until extended.
struct WorldBox {
    glm::dvec3 min{std::numeric_limits<double>::infinity()};
    glm::dvec3 max{-std::numeric_limits<double>::infinity()};
};

inline bool isEmpty(const WorldBox& b) {
    return !(b.min.x <= b.max.x && b.min.y <= b.max.y && b.min.z <= b.max.z);
}
inline void extend(WorldBox& b, const glm::dvec3& p) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
}
inline void extend(WorldBox& b, const Aabb& box) {
    if (isEmpty(box)) return;
    extend(b, glm::dvec3(box.min));
    extend(b, glm::dvec3(box.max));
}

// The box in float, as culling's boxes are (to the nearest float: no place that needs the outward
// rounding of an object's box should use it).
inline Aabb floatBox(const WorldBox& b) {
    return isEmpty(b) ? Aabb{} : Aabb{glm::vec3(b.min), glm::vec3(b.max)};
}

// The teapot field of both papers: `count` teapots of random size and orientation placed
// uniformly (seeded) in a box.
struct TeapotFieldSpec {
    uint32_t count = 1000;
    WorldBox region{glm::dvec3(-50, 0, -200), glm::dvec3(50, 10, 0)};
    double size_min_m = 1.0;  // teapot height
    double size_max_m = 3.0;
    uint32_t tessellation = 6;  // segments per Bézier patch side
};

// A street grid of buildings of varied footprint and height: streets give long views, buildings
// hide most of the city. Lanes: one closed loop per street ring for cars.
struct CitySpec {
    uint32_t blocks_x = 8;       // city blocks along x
    uint32_t blocks_z = 8;       // city blocks along z
    double block_size_m = 40.0;  // side of a block (buildings inside, streets around)
    double street_width_m = 12.0;
    double height_min_m = 8.0;  // building heights
    double height_max_m = 60.0;
    uint32_t buildings_per_block = 4;  // per block, at most; footprints vary
};

// Rows of shelves without back panels, filled with many small books: the books are the
// occluders (the library of Kovalčík & Sochor). Lanes: the aisles between rows, for people.
struct LibrarySpec {
    uint32_t rows = 8;              // rows of shelves
    uint32_t shelves_per_row = 6;   // shelf units along a row
    uint32_t levels = 5;            // boards per shelf unit
    uint32_t books_per_level = 30;  // books standing on one board
    double aisle_width_m = 2.0;
};

// A dense industrial structure (pipes, tanks, walkways, girders) with high depth complexity, an
// analogue of the power-plant model. Lanes: walkways, and loops through the structure for fliers.
struct PlantSpec {
    uint32_t units_x = 4;         // process units along x
    uint32_t units_z = 4;         // process units along z
    double unit_size_m = 20.0;    // footprint side of a unit
    uint32_t floors = 3;          // storeys of girders and walkways per unit
    double floor_height_m = 6.0;  // storey height (walkway clearance is about 3.3 m of it)
    uint32_t pipes_per_unit = 24;
    uint32_t tanks_per_unit = 3;
};

// Optional replication so that a small model can make a large scene.
struct GltfReplication {
    enum class Mode : uint8_t { None, Grid, Random };
    Mode mode = Mode::None;
    uint32_t count_x = 1, count_z = 1;  // grid: copies along x and z
    double spacing_m = 0.0;             // grid: distance between copies (0 = model size + 10%)
    uint32_t count = 1;                 // random: number of copies
    WorldBox region;                    // random: where copies are placed (their origins)
    bool random_yaw = true;             // random: rotate each copy about y
};

// How a glTF source's node animations play (docs/scenario-gltf.md, "Animations"). An
// animation's own time is time_offset + phase + speed · (simulation time), wrapped by `mode`
// over its own duration.
enum class AnimationMode : uint8_t { Loop, Clamp, PingPong };

struct AnimationPick {
    std::string name;    // by name when not empty
    uint32_t index = 0;  // else by index
};

struct GltfAnimationSpec {
    bool play_all = true;             // "play": "all" (the default)
    std::vector<AnimationPick> play;  // "play": [names or indices]; empty with !play_all: none
    double speed = 1.0;               // >= 0
    AnimationMode mode = AnimationMode::Loop;
    double time_offset_s = 0.0;  // the animations' time at simulation time 0
    bool random_phase = false;   // each copy starts at its own seeded phase
};

// What a glTF source does with its file's KHR_lights_punctual lights: read them, its directional
// lights casting shadows (the default); read them, none casting; or leave them out.
enum class GltfLights : uint8_t { Shadows, NoShadows, Ignore };

struct GltfSourceSpec {
    std::filesystem::path path;  // resolved against the scenario file's folder
    double scale = 1.0;          // uniform scale applied to the whole model
    glm::dvec3 offset{0.0};      // translation applied after scaling (metres)
    GltfReplication replicate;
    GltfAnimationSpec animation;
    bool place = true;  // false: only movers' "spawn": {"model": ...} place it
    GltfLights lights = GltfLights::Shadows;
};

enum class SourceType : uint8_t { Teapots, Gltf, City, Library, Plant };

// Whether a software depth buffer (the `masked` culler) may rasterise an object as an occluder:
// when it is large enough on screen (the default), always, or never. A source's "occluders" key
// sets it for its objects; a glTF node's extras ("occsim_occluder") for that node's.
enum class OccluderRole : uint8_t { BySize, Always, Never };

struct SceneSourceSpec {
    SourceType type = SourceType::Teapots;
    OccluderRole occluders = OccluderRole::BySize;
    std::variant<TeapotFieldSpec, GltfSourceSpec, CitySpec, LibrarySpec, PlantSpec> spec;
};

}  // namespace occsim
