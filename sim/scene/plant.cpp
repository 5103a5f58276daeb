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
#include "sim/scene/generators.h"

#include "sim/scene/primitives.h"
#include "occsim/culling/geometry/random.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace occsim {
namespace {

constexpr double kCrack = 0.01;  // between neighbouring objects, which never touch
constexpr double kLaneHeight = 0.02;
constexpr double kGroundTop = -0.25;
constexpr double kPadDepth = 0.2;
constexpr double kPadMargin = 1.3;  // pad beyond the frame (room for the risers)
constexpr double kSlabThickness = 0.15;
constexpr double kSlabGap = 0.05;     // slabs stop short of the column lines
constexpr double kBeamDepth = 0.45;   // I-beam height under a floor
constexpr double kBeamWidth = 0.25;   // its flange width
constexpr double kColumnWidth = 0.4;  // ground-storey columns; 8 % thinner per storey up
constexpr double kColumnTaper = 0.92;
constexpr double kColumnClear = kColumnWidth / 2 + kCrack;  // beams and floors keep off columns
constexpr double kSpliceAboveFloor = 1.0;  // column segments join 1 m above each floor
constexpr double kClearOfColumn = 0.45;    // pipes and tanks keep this far from column lines
constexpr double kCorridorHeadroom = 3.3;  // nothing crosses a corridor lower above its floor
constexpr double kFlierHeight = 1.5;       // fliers' corridor lanes above the floor
constexpr double kFlierHeadroom = 2.0;     // ... when this much room is left above them
constexpr uint32_t kBaysPerSide = 3;
constexpr uint32_t kPipeSegments = 16;
constexpr uint32_t kTankSegments = 24;
constexpr int kPipeTries = 16;

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

struct Meshes {
    uint32_t box = 0, ibeam = 0, slab = 0, pipe = 0, tank_cylinder = 0, sphere = 0;
    std::map<uint32_t, uint32_t> domed;  // height ratio -> mesh
};

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

struct Unit {
    double x = 0, z = 0;  // corner of the unit's frame (where column lines 0 and 0 cross)
};

class PlantBuilder {
public:
    PlantBuilder(const PlantSpec& spec, uint64_t seed) : spec_(spec), rng_(seed) {
        s_ = spec.unit_size_m;
        bay_ = s_ / kBaysPerSide;
        gap_ = std::max(6.0, 0.35 * s_);
        pitch_ = s_ + gap_;
        hf_ = spec.floor_height_m;
        top_ = spec.floors * hf_;
        meshes_.box = addMesh(out_, makeBox(glm::vec3(1.0f)));
        meshes_.ibeam = addMesh(out_, iBeamMesh());
        meshes_.slab = addMesh(out_, baySlabMesh(bay_));
        meshes_.pipe = addMesh(out_, makeCylinder(1.0f, 1.0f, kPipeSegments));
        meshes_.tank_cylinder = addMesh(out_, makeCylinder(1.0f, 1.0f, kTankSegments));
        meshes_.sphere = addMesh(out_, makeSphere(1.0f, kTankSegments, kTankSegments / 2));
    }

    SourceOutput build() {
        const double width = spec_.units_x * pitch_ - gap_, depth = spec_.units_z * pitch_ - gap_;
        const double m = kPadMargin;
        out_.objects.push_back(placeUnitBox(meshes_.box, {-gap_, kGroundTop - 0.3, -gap_},
                                            {width + gap_, kGroundTop, depth + gap_}));
        for (uint32_t j = 0; j < spec_.units_z; ++j) {
            for (uint32_t i = 0; i < spec_.units_x; ++i) {
                const Unit u{i * pitch_, j * pitch_};
                out_.objects.push_back(placeUnitBox(meshes_.box, {u.x - m, -kPadDepth, u.z - m},
                                                    {u.x + s_ + m, 0.0, u.z + s_ + m}));
            }
        }
        for (uint32_t j = 0; j < spec_.units_z; ++j) {
            for (uint32_t i = 0; i < spec_.units_x; ++i) {
                buildUnit({i * pitch_, j * pitch_}, i + 1 < spec_.units_x);
            }
        }
        if (tanks_dropped_ > 0) {
            out_.warnings.push_back("plant: " + std::to_string(tanks_dropped_) +
                                    " tanks left out (a unit has room for 6, one per side bay)");
        }
        if (pipes_dropped_ > 0) {
            out_.warnings.push_back("plant: " + std::to_string(pipes_dropped_) +
                                    " pipes left out (no room clear of the other pipes and tanks)");
        }
        addLanes(width, depth);
        out_.region = sourceBounds(out_);
        for (const auto& lane : out_.lanes) {
            for (const glm::dvec3& p : lane) {  // room for a 2 m mover above every lane point
                extend(out_.region, glm::vec3(p));
                extend(out_.region, glm::vec3(p + glm::dvec3(0, 2, 0)));
            }
        }
        return std::move(out_);
    }

private:
    double line(uint32_t k) const { return k * bay_; }  // column line k of a unit, local
    double level(uint32_t k) const { return k * hf_; }  // underside of floor k's slab
    double floorTop(uint32_t k) const { return k == 0 ? 0.0 : level(k) + kSlabThickness; }
    // Underside of the beams carrying floor k.
    double beamBottom(uint32_t k) const { return level(k) - kCrack - kBeamDepth; }

    void buildUnit(const Unit& u, bool bridge_to_next) {
        // Tanks go into distinct side bays (j != 1), in random order.
        std::vector<uint32_t> side_bays;  // index i + 3 * j
        for (uint32_t j : {0u, 2u}) {
            for (uint32_t i = 0; i < kBaysPerSide; ++i) side_bays.push_back(i + kBaysPerSide * j);
        }
        for (uint32_t k = 0; k < side_bays.size(); ++k) {
            const auto left = static_cast<uint32_t>(side_bays.size()) - k;
            std::swap(side_bays[k], side_bays[k + rng_.below(left)]);
        }
        const uint32_t tanks =
            std::min<uint32_t>(spec_.tanks_per_unit, static_cast<uint32_t>(side_bays.size()));
        tanks_dropped_ += spec_.tanks_per_unit - tanks;
        std::vector<double> tank_top(kBaysPerSide * kBaysPerSide, -1.0);
        std::vector<Aabb> taken;  // tanks and pipes so far: new pipes must keep clear of them
        for (uint32_t t = 0; t < tanks; ++t) {
            const uint32_t bay = side_bays[t];
            tank_top[bay] = addTank(u, bay % kBaysPerSide, bay / kBaysPerSide, taken);
        }
        addColumns(u);
        addBeamsAndSlabs(u, tank_top, bridge_to_next);
        for (uint32_t p = 0; p < spec_.pipes_per_unit; ++p) addPipe(u, taken);
    }

    void addColumns(const Unit& u) {
        for (uint32_t a = 0; a <= kBaysPerSide; ++a) {
            for (uint32_t b = 0; b <= kBaysPerSide; ++b) {
                for (uint32_t k = 0; k < spec_.floors; ++k) {
                    const double y0 = k == 0 ? kCrack : level(k) + kSpliceAboveFloor + kCrack / 2;
                    const double y1 = k + 1 == spec_.floors
                                          ? top_ + kSpliceAboveFloor
                                          : level(k + 1) + kSpliceAboveFloor - kCrack / 2;
                    const double w = kColumnWidth * std::pow(kColumnTaper, k);
                    out_.objects.push_back(girder(meshes_.ibeam, {u.x + line(a), y0, u.z + line(b)},
                                                  1, y1 - y0, w, w));
                }
            }
        }
    }

    void addBeamsAndSlabs(const Unit& u, const std::vector<double>& tank_top, bool bridge_to_next) {
        const double span = bay_ - 2 * kColumnClear;
        for (uint32_t k = 1; k <= spec_.floors; ++k) {
            const double beam_y = beamBottom(k) + kBeamDepth / 2;  // centre line
            for (uint32_t a = 0; a <= kBaysPerSide; ++a) {
                for (uint32_t b = 0; b < kBaysPerSide; ++b) {
                    const double along = line(b) + kColumnClear;
                    out_.objects.push_back(girder(meshes_.ibeam,
                                                  {u.x + along, beam_y, u.z + line(a)}, 0, span,
                                                  kBeamWidth, kBeamDepth));
                    out_.objects.push_back(girder(meshes_.ibeam,
                                                  {u.x + line(a), beam_y, u.z + along}, 2, span,
                                                  kBeamWidth, kBeamDepth));
                }
            }
            // Floors: always in the corridor (the walkway), elsewhere at random, never through a
            // tank. One notched slab per bay.
            for (uint32_t j = 0; j < kBaysPerSide; ++j) {
                for (uint32_t i = 0; i < kBaysPerSide; ++i) {
                    const double chance = rng_.uniform();
                    const bool wanted = j == 1 || chance < (k == spec_.floors ? 0.7 : 0.5);
                    if (!wanted || tank_top[i + kBaysPerSide * j] > beamBottom(k) - kCrack)
                        continue;
                    PlacedObject slab;
                    slab.mesh = meshes_.slab;
                    slab.position = {u.x + line(i), level(k), u.z + line(j)};
                    out_.objects.push_back(slab);
                }
            }
            // A bridge to the next unit's corridor on every storey below the roof, carried by
            // two beams continuing the corridor's column lines.
            if (bridge_to_next && k < spec_.floors) {
                const double x0 = u.x + s_, x1 = u.x + pitch_;
                out_.objects.push_back(placeUnitBox(
                    meshes_.box, {x0 + kSlabGap, level(k), u.z + line(1) + kColumnClear},
                    {x1 - kSlabGap, level(k) + kSlabThickness, u.z + line(2) - kColumnClear}));
                for (uint32_t a : {1u, 2u}) {
                    out_.objects.push_back(girder(meshes_.ibeam,
                                                  {x0 + kColumnClear, beam_y, u.z + line(a)}, 0,
                                                  gap_ - 2 * kColumnClear, kBeamWidth, kBeamDepth));
                }
            }
        }
    }

    // A tank in side bay (i, j): a domed vertical cylinder, a sphere on four legs or a horizontal
    // cylinder on two saddles, 1 cm above the pad, its parts 1 cm apart. Adds its box to `taken`
    // and returns the height of its top.
    double addTank(const Unit& u, uint32_t i, uint32_t j, std::vector<Aabb>& taken) {
        const double inner = bay_ - 2 * kClearOfColumn;  // clear width of the bay
        const double cx = u.x + line(i) + bay_ / 2, cz = u.z + line(j) + bay_ / 2;
        const double kind = rng_.uniform();
        const double size = rng_.uniform(0.35, 0.48);
        const uint32_t storeys = 1 + rng_.below(std::min(spec_.floors, 3u));
        const size_t first = out_.objects.size();
        double top = 0.0;
        if (kind < 0.5) {
            const double r = size * inner;
            const double wanted = storeys * hf_ - 1.0;  // cylinder plus dome
            const auto ratio =
                static_cast<uint32_t>(std::clamp(std::lround(wanted / r - 1.0), 1L, 8L));
            auto [it, added] =
                meshes_.domed.try_emplace(ratio, static_cast<uint32_t>(out_.meshes.size()));
            if (added) out_.meshes.push_back(domedTankMesh(ratio));
            PlacedObject tank;
            tank.mesh = it->second;
            tank.position = {cx, kCrack, cz};
            tank.linear = glm::mat3(static_cast<float>(r));
            out_.objects.push_back(tank);
            top = kCrack + r * (ratio + 1);
        } else if (kind < 0.75) {
            const double r = size * inner, lift = 1.5, centre = lift + r;
            PlacedObject tank;
            tank.mesh = meshes_.sphere;
            tank.position = {cx, lift, cz};
            tank.linear = glm::mat3(static_cast<float>(r));
            out_.objects.push_back(tank);
            // Legs end 1 cm below the sphere, measured at their corner nearest its axis (the
            // tessellated sphere lies inside the true one, so it clears the mesh too).
            const double leg = 0.7 * r, half = 0.125;
            const double nearest = std::sqrt(2.0) * (leg - half);
            const double leg_top = centre - std::sqrt(r * r - nearest * nearest) - kCrack;
            for (double dx : {-leg, leg}) {
                for (double dz : {-leg, leg}) {
                    out_.objects.push_back(girder(meshes_.ibeam, {cx + dx, kCrack, cz + dz}, 1,
                                                  leg_top - kCrack, 2 * half, 2 * half));
                }
            }
            top = lift + 2 * r;
        } else {
            const double r = std::min(1.3, 0.28 * inner), length = inner * rng_.uniform(0.8, 1.0);
            const double axis_y = r + 0.6;
            out_.objects.push_back(
                cylinder(meshes_.tank_cylinder, {cx - length / 2, axis_y, cz}, 0, length, r));
            for (double dx : {-0.3 * length, 0.3 * length}) {
                out_.objects.push_back(
                    placeUnitBox(meshes_.box, {cx + dx - 0.15, kCrack, cz - 0.7 * r},
                                 {cx + dx + 0.15, axis_y - r - kCrack, cz + 0.7 * r}));
            }
            top = axis_y + r;
        }
        Aabb box;
        for (size_t o = first; o < out_.objects.size(); ++o)
            extend(box, objectBox(out_.objects[o]));
        taken.push_back({box.min - glm::vec3(kCrack), box.max + glm::vec3(kCrack)});
        return top;
    }

    Aabb objectBox(const PlacedObject& o) const {
        glm::mat4 m(o.linear);
        m[3] = glm::vec4(0, 0, 0, 1);
        Aabb box = transformAabb(meshBounds(out_.meshes[o.mesh]), m);
        return {glm::vec3(glm::dvec3(box.min) + o.position),
                glm::vec3(glm::dvec3(box.max) + o.position)};
    }

    // A local coordinate from u in [0, 1) inside one of the bands between column lines, `margin`
    // clear of the lines: any of the three bands, or only the two outside the corridor.
    double bandAt(double u, double margin, bool side_only) const {
        const uint32_t bands = side_only ? 2 : kBaysPerSide;
        const double scaled = u * bands;
        const auto index = std::min(static_cast<uint32_t>(scaled), bands - 1);
        const uint32_t band = side_only ? index * 2 : index;
        const double t = scaled - index;
        const double lo = line(band) + kClearOfColumn + margin,
                     hi = line(band + 1) - kClearOfColumn - margin;
        return lo < hi ? lo + t * (hi - lo) : 0.5 * (lo + hi);
    }

    // One pipe: along x in a side band, along z high above the corridor, or a riser outside the
    // frame. Each try draws the same count of numbers, so a pipe's layout depends only on the
    // pipes and tanks before it.
    void addPipe(const Unit& u, std::vector<Aabb>& taken) {
        for (int attempt = 0; attempt < kPipeTries; ++attempt) {
            const double kind = rng_.uniform();
            const double r = 0.08 + 0.37 * std::pow(rng_.uniform(), 2.0);
            const uint32_t storey = rng_.below(spec_.floors);
            const double a = rng_.uniform(), b = rng_.uniform(), c = rng_.uniform();
            const double start = rng_.uniform(0.3, bay_), end = rng_.uniform(s_ - bay_, s_ - 0.3);
            const double floor = floorTop(storey), ceiling = beamBottom(storey + 1) - kCrack;
            const double z_low = floor + kCorridorHeadroom + r, z_high = ceiling - r;
            const double x_low = floor + 0.6 + r, x_high = ceiling - r;
            glm::dvec3 from;
            int axis = 0;
            double length = 0.0;
            if (kind < 0.3 && z_low < z_high) {  // along z, crossing the corridor overhead
                from = {u.x + bandAt(a, r, false), z_low + b * (z_high - z_low), u.z + start};
                axis = 2;
                length = end - start;
            } else if (kind < 0.75 && x_low < x_high) {  // along x, beside the corridor
                from = {u.x + start, x_low + b * (x_high - x_low), u.z + bandAt(a, r, true)};
                axis = 0;
                length = end - start;
            } else {
                // A riser just outside the frame, from the pad up through one or more storeys
                // (those reaching the roof stand above it); on the sides facing the bridges, clear
                // of the corridor.
                const auto side = static_cast<uint32_t>(a * 4) % 4;
                const double out = 0.3 + r;  // clear of the columns and outer beams
                double along = 0.3 + b * (s_ - 0.6);
                if (side < 2 && along > line(1) - out - 0.2 && along < line(2) + out + 0.2) {
                    along = along < s_ / 2 ? line(1) - out - 0.2 : line(2) + out + 0.2;
                }
                const double across = side % 2 == 0 ? -out : s_ + out;
                from = side < 2 ? glm::dvec3(u.x + across, kCrack, u.z + along)
                                : glm::dvec3(u.x + along, kCrack, u.z + across);
                axis = 1;
                const uint32_t up = storey + 1;
                length = (up == spec_.floors ? top_ + 0.5 + 2.5 * c : beamBottom(up)) - kCrack;
            }
            const Aabb box = cylinderBox(from, axis, length, r);
            if (overlapsAny(box, taken)) continue;
            out_.objects.push_back(cylinder(meshes_.pipe, from, axis, length, r));
            taken.push_back({box.min - glm::vec3(kCrack), box.max + glm::vec3(kCrack)});
            return;
        }
        ++pipes_dropped_;
    }

    void addLanes(double width, double depth) {
        const double y = kLaneHeight;
        const double ring_out = kPadMargin + (gap_ - 2 * kPadMargin) / 4;  // frame to ring road
        for (uint32_t j = 0; j < spec_.units_z; ++j) {
            for (uint32_t i = 0; i < spec_.units_x; ++i) {
                const double x = i * pitch_, z = j * pitch_;
                out_.lanes.push_back(
                    ring(x - ring_out, z - ring_out, x + s_ + ring_out, z + s_ + ring_out, y));
            }
        }
        const double x0 = 0.6, x1 = width - 0.6;
        for (uint32_t j = 0; j < spec_.units_z; ++j) {
            const double mid = j * pitch_ + s_ / 2, half = s_ / 12;
            for (uint32_t k = 0; k < spec_.floors; ++k) {
                const double floor = floorTop(k);
                out_.lanes.push_back(ring(x0, mid - half, x1, mid + half, floor + y));
                if (beamBottom(k + 1) - floor >= kFlierHeight + kFlierHeadroom) {
                    out_.lanes.push_back(
                        ring(x0, mid - half, x1, mid + half, floor + kFlierHeight));
                }
                out_.lanes.push_back(ring(-ring_out, j * pitch_ - ring_out, width + ring_out,
                                          j * pitch_ + s_ + ring_out, level(k) + 3.0));
            }
        }
        out_.lanes.push_back(
            ring(-gap_ / 2, -gap_ / 2, width + gap_ / 2, depth + gap_ / 2, top_ + 8.0));
    }

    const PlantSpec& spec_;
    Rng rng_;
    SourceOutput out_;
    Meshes meshes_;
    double s_ = 0, bay_ = 0, gap_ = 0, pitch_ = 0, hf_ = 0, top_ = 0;
    uint32_t tanks_dropped_ = 0, pipes_dropped_ = 0;
};

}  // namespace

SourceOutput generatePlant(const PlantSpec& spec, uint64_t seed) {
    if (spec.units_x == 0 || spec.units_z == 0 || spec.floors == 0 || !(spec.unit_size_m > 0) ||
        !(spec.floor_height_m > 0)) {
        throw std::invalid_argument("generatePlant: invalid spec");
    }
    return PlantBuilder(spec, seed).build();
}

}  // namespace occsim
