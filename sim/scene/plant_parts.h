// The plant generator's parts, shared by its two files: the structure (plant.cpp: frames,
// floors, bridges, lanes) and the equipment (plant_equipment.cpp: tanks and pipes). plant.cpp
// describes the layout. Internal to sim/scene.
#pragma once

#include <map>
#include <vector>

#include "occsim/culling/geometry/random.h"
#include "sim/scene/generators.h"

namespace occsim::plant_detail {

inline constexpr double kCrack = 0.01;  // between neighbouring objects, which never touch
inline constexpr double kLaneHeight = 0.02;
inline constexpr double kGroundTop = -0.25;
inline constexpr double kPadDepth = 0.2;
inline constexpr double kPadMargin = 1.3;  // pad beyond the frame (room for the risers)
inline constexpr double kSlabThickness = 0.15;
inline constexpr double kSlabGap = 0.05;     // slabs stop short of the column lines
inline constexpr double kBeamDepth = 0.45;   // I-beam height under a floor
inline constexpr double kBeamWidth = 0.25;   // its flange width
inline constexpr double kColumnWidth = 0.4;  // ground-storey columns; 8 % thinner per storey up
inline constexpr double kColumnTaper = 0.92;
inline constexpr double kColumnClear =
    kColumnWidth / 2 + kCrack;                    // beams and floors keep off columns
inline constexpr double kSpliceAboveFloor = 1.0;  // column segments join 1 m above each floor
inline constexpr double kClearOfColumn = 0.45;    // pipes and tanks keep this far from column lines
inline constexpr double kCorridorHeadroom =
    3.3;                                       // nothing crosses a corridor lower above its floor
inline constexpr double kFlierHeight = 1.5;    // fliers' corridor lanes above the floor
inline constexpr double kFlierHeadroom = 2.0;  // ... when this much room is left above them
inline constexpr uint32_t kBaysPerSide = 3;
inline constexpr uint32_t kPipeSegments = 16;
inline constexpr uint32_t kTankSegments = 24;
inline constexpr int kPipeTries = 16;

struct Meshes {
    uint32_t box = 0, ibeam = 0, slab = 0, pipe = 0, tank_cylinder = 0, sphere = 0;
    std::map<uint32_t, uint32_t> domed;  // height ratio -> mesh
};

struct Unit {
    double x = 0, z = 0;  // corner of the unit's frame (where column lines 0 and 0 cross)
};

// What the parts of one plant share while it is built: the spec, the random stream (drawn in a
// fixed order, so that one seed gives one plant), the output, the meshes and the measures.
struct PlantContext {
    PlantContext(const PlantSpec& spec_in, uint64_t seed);

    double line(uint32_t k) const { return k * bay; }  // column line k of a unit, local
    double level(uint32_t k) const { return k * hf; }  // underside of floor k's slab
    double floorTop(uint32_t k) const { return k == 0 ? 0.0 : level(k) + kSlabThickness; }
    // Underside of the beams carrying floor k.
    double beamBottom(uint32_t k) const { return level(k) - kCrack - kBeamDepth; }

    const PlantSpec& spec;
    Rng rng;
    SourceOutput out;
    Meshes meshes;
    // Unit size, bay, gap between units, their pitch, storey height, roof height (metres).
    double s = 0, bay = 0, gap = 0, pitch = 0, hf = 0, top = 0;
    uint32_t tanks_dropped = 0, pipes_dropped = 0;
};

// Shapes (plant.cpp).
PlacedObject girder(uint32_t mesh, glm::dvec3 from, int axis, double length, double width,
                    double depth);
PlacedObject cylinder(uint32_t mesh, glm::dvec3 from, int axis, double length, double radius);
Aabb cylinderBox(glm::dvec3 from, int axis, double length, double radius);
bool overlapsAny(const Aabb& box, const std::vector<Aabb>& others);
MeshData domedTankMesh(uint32_t ratio);

// Equipment (plant_equipment.cpp).
// A tank in side bay (i, j): a domed vertical cylinder, a sphere on four legs or a horizontal
// cylinder on two saddles, 1 cm above the pad, its parts 1 cm apart. Adds its box to `taken`
// and returns the height of its top.
// Legs end 1 cm below the sphere, measured at their corner nearest its axis (the
// tessellated sphere lies inside the true one, so it clears the mesh too).
double addTank(PlantContext& c, const Unit& u, uint32_t i, uint32_t j, std::vector<Aabb>& taken);
// One pipe: along x in a side band, along z high above the corridor, or a riser outside the
// frame. Each try draws the same count of numbers, so a pipe's layout depends only on the
// pipes and tanks before it.
// A riser just outside the frame, from the pad up through one or more storeys
// (those reaching the roof stand above it); on the sides facing the bridges, clear
// of the corridor.
void addPipe(PlantContext& c, const Unit& u, std::vector<Aabb>& taken);

}  // namespace occsim::plant_detail
