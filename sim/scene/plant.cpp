// Plant: an analogue of the power-plant model both papers test on (Kovalčík & Sochor 2005 use a
// 2-million-triangle reduction of the UNC power plant; the CHC paper the full 13-million one): a
// dense industrial structure of girders, walkways, pipes and tanks, with "significant changes in
// visibility and depth complexity in its different parts": deep inside, layer upon layer of steel
// hides most of the plant; along its border looking out, almost nothing is hidden.
//
// Layout (metres, y up; each unit stands on a concrete pad whose top is y = 0, the ground between
// the pads is lower, at y = -0.25). units_x by units_z process units of unit_size (S) square,
// gap = max(6, 0.35 S) apart: unit (i, j) spans x in [i * pitch, i * pitch + S], z in
// [j * pitch, j * pitch + S], pitch = S + gap. Each unit is a steel frame of 4 x 4 columns (on
// the column lines at multiples of S/3) and `floors` storeys of floor_height. The middle row of
// bays along x (z in [S/3, 2S/3]) is a walkway corridor with a floor on every storey, joined to
// the next unit's by a bridge; the six side bays hold tanks and partial floors. Pipes run along x
// in the side bays at any height, along z only high enough (3.3 m above a floor) to leave the
// corridor clear, and vertically as risers just outside the frame.
//
// Objects, in this order: the ground, the pads, then per unit its tanks (with their legs or
// saddles), columns (one I-beam per storey, thinner storey by storey), beams (one per bay edge and
// level), floor slabs (one per bay and level), bridges and their beams, and pipes. Every girder,
// slab, pipe and tank is its own object; they share a unit box, a unit I-beam, a floor slab, two
// unit cylinders, a unit sphere and one domed-tank mesh per height ratio, stretched or rotated
// through `linear`.
//
// No two objects touch: beams stop 1 cm short of the columns and the floors above them, floors
// are notched around the columns, column segments leave 1 cm between storeys, everything stands
// 1 cm above its pad, and pipes are placed only where their box meets no tank and no other pipe
// (a pipe with no room after a few tries is left out, with a warning). Where two objects touch
// or cut into each other, their depths are equal along the contact line, and a pixel there whose
// depths tie exactly shows whichever object was drawn first, an error no culling decision caused.
//
// Lanes (a mover's base rests on the lane point, 2 cm above the surface under it): walkways on
// the ground around each unit, and along each row's corridor on every storey below the roof (on
// the floor slabs, across the bridges); fliers' loops through the same corridors 1.5 m above the
// floor (when the storey leaves 2 m of headroom above that), round each row of units in the gaps
// 3 m above every floor level, and one 8 m above the whole plant.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/scene/plant_parts.h"
#include "sim/scene/primitives.h"

namespace occsim::plant_detail {

// Proper rotations (determinant +1) taking a mesh's y axis, along which cylinders and I-beams
// are built, to x or to z. For I-beams the flanges (built facing +-z) end up facing +-y.
glm::mat3 yToX() { return glm::mat3(glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)); }
glm::mat3 yToZ() { return glm::mat3(glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1), glm::vec3(0, 1, 0)); }

// An I-beam along y, unit flange width (x), depth (z) and length: two flanges and a web.
MeshData iBeamMesh() {
    MeshData m;
    const float flange = 0.1f, web = 0.08f;
    appendBox(m, {-0.5f, 0, -0.5f}, {0.5f, 1, -0.5f + flange});
    appendBox(m, {-0.5f, 0, 0.5f - flange}, {0.5f, 1, 0.5f});
    appendBox(m, {-web / 2, 0, -0.5f + flange}, {web / 2, 1, 0.5f - flange});
    return m;
}

// The floor of one bay, from its corner (0, 0, 0) to (bay, thickness, bay): two overlapping
// slabs forming a cross, so that the square corners where the columns stand are left out.
MeshData baySlabMesh(double bay) {
    MeshData m;
    const auto b = static_cast<float>(bay), t = static_cast<float>(kSlabThickness);
    const auto g = static_cast<float>(kSlabGap), c = static_cast<float>(kColumnClear);
    appendBox(m, {g, 0, c}, {b - g, t, b - c});
    appendBox(m, {c, 0, g}, {b - c, t, b - g});
    return m;
}

// A vertical tank of unit radius: a cylinder `ratio` radii high under a hemispherical dome (a
// whole sphere whose lower half lies inside the cylinder).
MeshData domedTankMesh(uint32_t ratio) {
    MeshData m = makeCylinder(1.0f, static_cast<float>(ratio), kTankSegments);
    appendMesh(m, makeSphere(1.0f, kTankSegments, kTankSegments / 2),
               {0, static_cast<float>(ratio) - 1.0f, 0});
    return m;
}

uint32_t addMesh(SourceOutput& out, MeshData mesh) {
    out.meshes.push_back(std::move(mesh));
    return static_cast<uint32_t>(out.meshes.size() - 1);
}

// An I-beam from `from` running `length` along x, along z, or up (axis 0, 2 or 1); `from` is the
// middle of its start face. Horizontal beams have their flanges top and bottom.
PlacedObject girder(uint32_t mesh, glm::dvec3 from, int axis, double length, double width,
                    double depth) {
    PlacedObject o;
    o.mesh = mesh;
    o.position = from;
    const glm::mat3 scale = scaleMatrix(glm::vec3(glm::dvec3(width, length, depth)));
    o.linear = axis == 0 ? yToX() * scale : axis == 2 ? yToZ() * scale : scale;
    return o;
}

// A cylinder of `radius` from `from` (the centre of its start cap) running `length` along an axis.
PlacedObject cylinder(uint32_t mesh, glm::dvec3 from, int axis, double length, double radius) {
    PlacedObject o;
    o.mesh = mesh;
    o.position = from;
    const glm::mat3 scale = scaleMatrix(glm::vec3(glm::dvec3(radius, length, radius)));
    // The cylinder's radial plane is xz, so any rotation taking y to the axis will do.
    o.linear = axis == 0 ? yToX() * scale : axis == 2 ? yToZ() * scale : scale;
    return o;
}

// The box of a cylinder placed by cylinder() (axis-aligned, so exact).
Aabb cylinderBox(glm::dvec3 from, int axis, double length, double radius) {
    glm::dvec3 lo = from - glm::dvec3(radius), hi = from + glm::dvec3(radius);
    lo[axis] = from[axis];
    hi[axis] = from[axis] + length;
    return {glm::vec3(lo), glm::vec3(hi)};
}

bool overlapsAny(const Aabb& box, const std::vector<Aabb>& others) {
    for (const Aabb& o : others) {
        if (overlaps(box, o)) return true;
    }
    return false;
}

// A closed rectangle at height y, clockwise seen from above.
std::vector<glm::dvec3> ring(double x0, double z0, double x1, double z1, double y) {
    return {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};
}

PlantContext::PlantContext(const PlantSpec& spec_in, uint64_t seed) : spec(spec_in), rng(seed) {
    s = spec_in.unit_size_m;
    bay = s / kBaysPerSide;
    gap = std::max(6.0, 0.35 * s);
    pitch = s + gap;
    hf = spec_in.floor_height_m;
    top = spec_in.floors * hf;
    meshes.box = addMesh(out, makeBox(glm::vec3(1.0f)));
    meshes.ibeam = addMesh(out, iBeamMesh());
    meshes.slab = addMesh(out, baySlabMesh(bay));
    meshes.pipe = addMesh(out, makeCylinder(1.0f, 1.0f, kPipeSegments));
    meshes.tank_cylinder = addMesh(out, makeCylinder(1.0f, 1.0f, kTankSegments));
    meshes.sphere = addMesh(out, makeSphere(1.0f, kTankSegments, kTankSegments / 2));
}

namespace {

void addColumns(PlantContext& c, const Unit& u) {
    for (uint32_t a = 0; a <= kBaysPerSide; ++a) {
        for (uint32_t b = 0; b <= kBaysPerSide; ++b) {
            for (uint32_t k = 0; k < c.spec.floors; ++k) {
                const double y0 = k == 0 ? kCrack : c.level(k) + kSpliceAboveFloor + kCrack / 2;
                const double y1 = k + 1 == c.spec.floors
                                      ? c.top + kSpliceAboveFloor
                                      : c.level(k + 1) + kSpliceAboveFloor - kCrack / 2;
                const double w = kColumnWidth * std::pow(kColumnTaper, k);
                c.out.objects.push_back(girder(
                    c.meshes.ibeam, {u.x + c.line(a), y0, u.z + c.line(b)}, 1, y1 - y0, w, w));
            }
        }
    }
}

void addBeamsAndSlabs(PlantContext& c, const Unit& u, const std::vector<double>& tank_top,
                      bool bridge_to_next) {
    const double span = c.bay - 2 * kColumnClear;
    for (uint32_t k = 1; k <= c.spec.floors; ++k) {
        const double beam_y = c.beamBottom(k) + kBeamDepth / 2;  // centre line
        for (uint32_t a = 0; a <= kBaysPerSide; ++a) {
            for (uint32_t b = 0; b < kBaysPerSide; ++b) {
                const double along = c.line(b) + kColumnClear;
                c.out.objects.push_back(girder(c.meshes.ibeam,
                                               {u.x + along, beam_y, u.z + c.line(a)}, 0, span,
                                               kBeamWidth, kBeamDepth));
                c.out.objects.push_back(girder(c.meshes.ibeam,
                                               {u.x + c.line(a), beam_y, u.z + along}, 2, span,
                                               kBeamWidth, kBeamDepth));
            }
        }
        // Floors: always in the corridor (the walkway), elsewhere at random, never through a
        // tank. One notched slab per bay.
        for (uint32_t j = 0; j < kBaysPerSide; ++j) {
            for (uint32_t i = 0; i < kBaysPerSide; ++i) {
                const double chance = c.rng.uniform();
                const bool wanted = j == 1 || chance < (k == c.spec.floors ? 0.7 : 0.5);
                if (!wanted || tank_top[i + kBaysPerSide * j] > c.beamBottom(k) - kCrack) continue;
                PlacedObject slab;
                slab.mesh = c.meshes.slab;
                slab.position = {u.x + c.line(i), c.level(k), u.z + c.line(j)};
                c.out.objects.push_back(slab);
            }
        }
        // A bridge to the next unit's corridor on every storey below the roof, carried by
        // two beams continuing the corridor's column lines.
        if (bridge_to_next && k < c.spec.floors) {
            const double x0 = u.x + c.s, x1 = u.x + c.pitch;
            c.out.objects.push_back(placeUnitBox(
                c.meshes.box, {x0 + kSlabGap, c.level(k), u.z + c.line(1) + kColumnClear},
                {x1 - kSlabGap, c.level(k) + kSlabThickness, u.z + c.line(2) - kColumnClear}));
            for (uint32_t a : {1u, 2u}) {
                c.out.objects.push_back(girder(c.meshes.ibeam,
                                               {x0 + kColumnClear, beam_y, u.z + c.line(a)}, 0,
                                               c.gap - 2 * kColumnClear, kBeamWidth, kBeamDepth));
            }
        }
    }
}

void buildUnit(PlantContext& c, const Unit& u, bool bridge_to_next) {
    // Tanks go into distinct side bays (j != 1), in random order.
    std::vector<uint32_t> side_bays;  // index i + 3 * j
    for (uint32_t j : {0u, 2u}) {
        for (uint32_t i = 0; i < kBaysPerSide; ++i) side_bays.push_back(i + kBaysPerSide * j);
    }
    for (uint32_t k = 0; k < side_bays.size(); ++k) {
        const auto left = static_cast<uint32_t>(side_bays.size()) - k;
        std::swap(side_bays[k], side_bays[k + c.rng.below(left)]);
    }
    const uint32_t tanks =
        std::min<uint32_t>(c.spec.tanks_per_unit, static_cast<uint32_t>(side_bays.size()));
    c.tanks_dropped += c.spec.tanks_per_unit - tanks;
    std::vector<double> tank_top(kBaysPerSide * kBaysPerSide, -1.0);
    std::vector<Aabb> taken;  // tanks and pipes so far: new pipes must keep clear of them
    for (uint32_t t = 0; t < tanks; ++t) {
        const uint32_t bay = side_bays[t];
        tank_top[bay] = addTank(c, u, bay % kBaysPerSide, bay / kBaysPerSide, taken);
    }
    addColumns(c, u);
    addBeamsAndSlabs(c, u, tank_top, bridge_to_next);
    for (uint32_t p = 0; p < c.spec.pipes_per_unit; ++p) addPipe(c, u, taken);
}

void addLanes(PlantContext& c, double width, double depth) {
    const double y = kLaneHeight;
    const double ring_out = kPadMargin + (c.gap - 2 * kPadMargin) / 4;  // frame to ring road
    for (uint32_t j = 0; j < c.spec.units_z; ++j) {
        for (uint32_t i = 0; i < c.spec.units_x; ++i) {
            const double x = i * c.pitch, z = j * c.pitch;
            c.out.lanes.push_back(
                ring(x - ring_out, z - ring_out, x + c.s + ring_out, z + c.s + ring_out, y));
        }
    }
    const double x0 = 0.6, x1 = width - 0.6;
    for (uint32_t j = 0; j < c.spec.units_z; ++j) {
        const double mid = j * c.pitch + c.s / 2, half = c.s / 12;
        for (uint32_t k = 0; k < c.spec.floors; ++k) {
            const double floor = c.floorTop(k);
            c.out.lanes.push_back(ring(x0, mid - half, x1, mid + half, floor + y));
            if (c.beamBottom(k + 1) - floor >= kFlierHeight + kFlierHeadroom) {
                c.out.lanes.push_back(ring(x0, mid - half, x1, mid + half, floor + kFlierHeight));
            }
            c.out.lanes.push_back(ring(-ring_out, j * c.pitch - ring_out, width + ring_out,
                                       j * c.pitch + c.s + ring_out, c.level(k) + 3.0));
        }
    }
    c.out.lanes.push_back(
        ring(-c.gap / 2, -c.gap / 2, width + c.gap / 2, depth + c.gap / 2, c.top + 8.0));
}

}  // namespace

SourceOutput buildPlant(PlantContext& c) {
    const double width = c.spec.units_x * c.pitch - c.gap, depth = c.spec.units_z * c.pitch - c.gap;
    const double m = kPadMargin;
    c.out.objects.push_back(placeUnitBox(c.meshes.box, {-c.gap, kGroundTop - 0.3, -c.gap},
                                         {width + c.gap, kGroundTop, depth + c.gap}));
    for (uint32_t j = 0; j < c.spec.units_z; ++j) {
        for (uint32_t i = 0; i < c.spec.units_x; ++i) {
            const Unit u{i * c.pitch, j * c.pitch};
            c.out.objects.push_back(placeUnitBox(c.meshes.box, {u.x - m, -kPadDepth, u.z - m},
                                                 {u.x + c.s + m, 0.0, u.z + c.s + m}));
        }
    }
    for (uint32_t j = 0; j < c.spec.units_z; ++j) {
        for (uint32_t i = 0; i < c.spec.units_x; ++i) {
            buildUnit(c, {i * c.pitch, j * c.pitch}, i + 1 < c.spec.units_x);
        }
    }
    if (c.tanks_dropped > 0) {
        c.out.warnings.push_back("plant: " + std::to_string(c.tanks_dropped) +
                                 " tanks left out (a unit has room for 6, one per side bay)");
    }
    if (c.pipes_dropped > 0) {
        c.out.warnings.push_back("plant: " + std::to_string(c.pipes_dropped) +
                                 " pipes left out (no room clear of the other pipes and tanks)");
    }
    addLanes(c, width, depth);
    c.out.region = sourceBounds(c.out);
    for (const auto& lane : c.out.lanes) {
        for (const glm::dvec3& p : lane) {  // room for a 2 m mover above every lane point
            extend(c.out.region, p);
            extend(c.out.region, p + glm::dvec3(0, 2, 0));
        }
    }
    return std::move(c.out);
}

}  // namespace occsim::plant_detail

namespace occsim {

SourceOutput generatePlant(const PlantSpec& spec, uint64_t seed) {
    if (spec.units_x == 0 || spec.units_z == 0 || spec.floors == 0 || !(spec.unit_size_m > 0) ||
        !(spec.floor_height_m > 0)) {
        throw std::invalid_argument("generatePlant: invalid spec");
    }
    plant_detail::PlantContext context(spec, seed);
    return plant_detail::buildPlant(context);
}

}  // namespace occsim
