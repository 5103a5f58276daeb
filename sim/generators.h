// Procedural scene generators modelled on the test scenes of the papers. Each is seeded and
// scalable, deterministic for a given spec and seed, and returns a SourceOutput (meshes, placed
// objects, lanes for movers). Units: metres. See docs/scenario-generators.md for the scenario keys.
#pragma once

#include "sim/scene_source.h"

#include <cstdint>

namespace occsim {

// A street grid of buildings of varied footprint and height: streets give long views, buildings
// hide most of the city. Lanes: one closed loop per street ring for cars.
struct CitySpec {
    uint32_t blocks_x = 8;           // city blocks along x
    uint32_t blocks_z = 8;           // city blocks along z
    double block_size_m = 40.0;      // side of a block (buildings inside, streets around)
    double street_width_m = 12.0;
    double height_min_m = 8.0;       // building heights
    double height_max_m = 60.0;
    uint32_t buildings_per_block = 4;  // per block, at most; footprints vary
};

// Rows of shelves without back panels, filled with many small books: the books are the
// occluders (the library of Kovalčík & Sochor). Lanes: the aisles between rows, for people.
struct LibrarySpec {
    uint32_t rows = 8;               // rows of shelves
    uint32_t shelves_per_row = 6;    // shelf units along a row
    uint32_t levels = 5;             // boards per shelf unit
    uint32_t books_per_level = 30;   // books standing on one board
    double aisle_width_m = 2.0;
};

// A dense industrial structure (pipes, tanks, walkways, girders) with high depth complexity, an
// analogue of the power-plant model. Lanes: walkways, and loops through the structure for fliers.
struct PlantSpec {
    uint32_t units_x = 4;            // process units along x
    uint32_t units_z = 4;            // process units along z
    double unit_size_m = 20.0;       // footprint side of a unit
    uint32_t floors = 3;             // storeys of girders and walkways per unit
    double floor_height_m = 6.0;     // storey height (walkway clearance is about 3.3 m of it)
    uint32_t pipes_per_unit = 24;
    uint32_t tanks_per_unit = 3;
};

SourceOutput generateCity(const CitySpec& spec, uint64_t seed);
SourceOutput generateLibrary(const LibrarySpec& spec, uint64_t seed);
SourceOutput generatePlant(const PlantSpec& spec, uint64_t seed);

}  // namespace occsim
