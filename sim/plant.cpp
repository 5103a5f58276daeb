// Plant: an analogue of the power-plant model both papers test on (Kovalčík & Sochor 2005 use a
// 2-million-triangle reduction of the UNC power plant; the CHC paper the full 13-million one): a
// dense industrial structure of girders, walkways, pipes and tanks, with "significant changes in
// visibility and depth complexity in its different parts": deep inside, layer upon layer of steel
// hides most of the plant; along its border looking out, almost nothing is hidden.
//
// Layout (metres, y up; the ground is at y = -0.02, each unit stands on a concrete pad whose top is
// y = 0). units_x by units_z process units of unit_size (S) square, gap = max(6, 0.35 S) apart:
// unit (i, j) spans x in [i * pitch, i * pitch + S], z in [j * pitch, j * pitch + S], pitch =
// S + gap. Each unit is a steel frame of 4 x 4 columns (at multiples of S/3) and `floors` storeys
// of floor_height; the middle row of bays along x (z in [S/3, 2S/3]) is a walkway corridor with a
// floor on every storey, joined to the next unit's by a bridge; the other six bays hold tanks and
// partial floors. Pipes run along x outside the corridor at any height, along z high enough
// (3.3 m above a floor) to leave the corridor clear, and vertically outside it.
//
// Objects, in this order: the ground, the pads, then per unit its columns (one I-beam per storey,
// thinner storey by storey), beams (one per bay edge and level), floor slabs (one per bay and
// level), bridges, tanks with their legs or saddles, and pipes. Every girder, slab, pipe and tank
// is its own object; they share a unit box, a unit I-beam, two unit cylinders, a unit sphere and
// one domed-tank mesh per height ratio, stretched or rotated through `linear`.
//
// Lanes (a mover's base rests on the lane point): walkways on the ground around each unit; along
// each row's corridor on every storey below the roof (on the floor slabs, across the bridges);
// fliers' loops through the same corridors 1.5 m above the floor, round each row of units in the
// gaps at every storey, and one above the whole plant.
#include "sim/generators.h"

#include "sim/primitives.h"
#include "sim/rng.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

namespace occsim {
namespace {

constexpr double kSlabThickness = 0.15;
constexpr double kSlabGap = 0.05;          // slabs stop short of the column lines
constexpr double kBeamDepth = 0.45;        // I-beam height under a floor
constexpr double kBeamWidth = 0.25;        // its flange width
constexpr double kBeamIntoSlab = 0.05;     // beam tops sit inside the slab: no coplanar faces
constexpr double kColumnWidth = 0.4;       // ground-storey columns; 8 % thinner per storey up
constexpr double kColumnTaper = 0.92;
constexpr double kSpliceAboveFloor = 1.0;  // column segments join 1 m above each floor
constexpr double kSink = 0.05;             // things standing on the pad reach into it
constexpr double kClearOfColumn = 0.45;    // pipes and tanks keep this far from column lines
constexpr double kCorridorHeadroom = 3.3;  // nothing crosses a corridor lower above its floor
constexpr double kFlierHeight = 1.5;       // fliers' lanes above the floor they fly over
constexpr uint32_t kBaysPerSide = 3;
constexpr uint32_t kPipeSegments = 16;
constexpr uint32_t kTankSegments = 24;

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

// A vertical tank of unit radius: a cylinder `ratio` radii high under a hemispherical dome (a
// whole sphere whose lower half lies inside the cylinder).
MeshData domedTankMesh(uint32_t ratio) {
    MeshData m = makeCylinder(1.0f, static_cast<float>(ratio), kTankSegments);
    appendMesh(m, makeSphere(1.0f, kTankSegments, kTankSegments / 2), {0, static_cast<float>(ratio) - 1.0f, 0});
    return m;
}

struct Meshes {
    uint32_t box, ibeam, pipe, tank_cylinder, sphere;
    std::map<uint32_t, uint32_t> domed;  // height ratio -> mesh
};

uint32_t addMesh(SourceOutput& out, MeshData mesh) {
    out.meshes.push_back(std::move(mesh));
    return static_cast<uint32_t>(out.meshes.size() - 1);
}

// An I-beam from `from` running `length` along x, along z, or up (axis 0, 2 or 1); `from` is the
// middle of its start face. Horizontal beams have their flanges top and bottom.
PlacedObject girder(const Meshes& meshes, glm::dvec3 from, int axis, double length, float width,
                    float depth) {
    PlacedObject o;
    o.mesh = meshes.ibeam;
    o.position = from;
    const glm::mat3 scale = scaleMatrix(glm::vec3(width, static_cast<float>(length), depth));
    o.linear = axis == 0 ? yToX() * scale : axis == 2 ? yToZ() * scale : scale;
    return o;
}

// A cylinder of `radius` from `from` (the centre of its start cap) running `length` along an axis.
PlacedObject cylinder(uint32_t mesh, glm::dvec3 from, int axis, double length, double radius) {
    PlacedObject o;
    o.mesh = mesh;
    o.position = from;
    const auto r = static_cast<float>(radius);
    const glm::mat3 scale = scaleMatrix(glm::vec3(r, static_cast<float>(length), r));
    // The cylinder's radial plane is xz, so any rotation taking y to the axis will do.
    o.linear = axis == 0 ? yToX() * scale : axis == 2 ? yToZ() * scale : scale;
    return o;
}

// A closed rectangle at height y, clockwise seen from above.
std::vector<glm::dvec3> ring(double x0, double z0, double x1, double z1, double y) {
    return {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};
}

struct Unit {
    double x = 0, z = 0;  // corner of the unit's frame (column line 0, 0)
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
        meshes_.pipe = addMesh(out_, makeCylinder(1.0f, 1.0f, kPipeSegments));
        meshes_.tank_cylinder = addMesh(out_, makeCylinder(1.0f, 1.0f, kTankSegments));
        meshes_.sphere = addMesh(out_, makeSphere(1.0f, kTankSegments, kTankSegments / 2));
    }

    SourceOutput build() {
        const double width = spec_.units_x * pitch_ - gap_, depth = spec_.units_z * pitch_ - gap_;
        out_.objects.push_back(placeUnitBox(meshes_.box, {-gap_, -0.3, -gap_},
                                            {width + gap_, -0.02, depth + gap_}));
        for (uint32_t j = 0; j < spec_.units_z; ++j) {
            for (uint32_t i = 0; i < spec_.units_x; ++i) {
                const Unit u{i * pitch_, j * pitch_};
                out_.objects.push_back(placeUnitBox(meshes_.box, {u.x - 1, -0.2, u.z - 1},
                                                    {u.x + s_ + 1, 0.0, u.z + s_ + 1}));
            }
        }
        for (uint32_t j = 0; j < spec_.units_z; ++j) {
            for (uint32_t i = 0; i < spec_.units_x; ++i) buildUnit({i * pitch_, j * pitch_}, i + 1 < spec_.units_x);
        }
        if (tanks_dropped_ > 0) {
            out_.warnings.push_back("plant: " + std::to_string(tanks_dropped_) +
                                    " tanks left out (a unit has room for 6, one per side bay)");
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

    void buildUnit(const Unit& u, bool bridge_to_next) {
        // Which side bays hold a tank, and up to what height (slabs stay out of its way).
        std::vector<uint32_t> side_bays;  // index i + 3 * j over bays with j != 1
        for (uint32_t j : {0u, 2u}) {
            for (uint32_t i = 0; i < kBaysPerSide; ++i) side_bays.push_back(i + kBaysPerSide * j);
        }
        for (uint32_t k = 0; k < side_bays.size(); ++k) {
            std::swap(side_bays[k], side_bays[k + rng_.below(static_cast<uint32_t>(side_bays.size()) - k)]);
        }
        const uint32_t tanks = std::min<uint32_t>(spec_.tanks_per_unit, static_cast<uint32_t>(side_bays.size()));
        tanks_dropped_ += spec_.tanks_per_unit - tanks;
        std::vector<double> tank_top(kBaysPerSide * kBaysPerSide, -1.0);
        std::vector<glm::dvec3> tank_discs;  // x, z, radius of each tank's footprint (local)
        for (uint32_t t = 0; t < tanks; ++t) {
            const uint32_t bay = side_bays[t];
            tank_top[bay] = addTank(u, bay % kBaysPerSide, bay / kBaysPerSide, tank_discs);
        }
        addColumns(u);
        addBeamsAndSlabs(u, tank_top, bridge_to_next);
        for (uint32_t p = 0; p < spec_.pipes_per_unit; ++p) addPipe(u, tank_discs);
    }

    void addColumns(const Unit& u) {
        for (uint32_t a = 0; a <= kBaysPerSide; ++a) {
            for (uint32_t b = 0; b <= kBaysPerSide; ++b) {
                for (uint32_t k = 0; k < spec_.floors; ++k) {
                    const double y0 = k == 0 ? -kSink : level(k) + kSpliceAboveFloor;
                    const double y1 = level(k + 1) + kSpliceAboveFloor;
                    const auto w = static_cast<float>(kColumnWidth * std::pow(kColumnTaper, k));
                    out_.objects.push_back(girder(meshes_, {u.x + line(a), y0, u.z + line(b)}, 1, y1 - y0, w, w));
                }
            }
        }
    }

    void addBeamsAndSlabs(const Unit& u, const std::vector<double>& tank_top, bool bridge_to_next) {
        const auto bw = static_cast<float>(kBeamWidth), bd = static_cast<float>(kBeamDepth);
        for (uint32_t k = 1; k <= spec_.floors; ++k) {
            const double beam_y = level(k) + kBeamIntoSlab - kBeamDepth / 2;  // beam centre line
            // Beams run centre to centre between columns; where two meet, their ends are inside
            // the column's web, flush against each other.
            for (uint32_t a = 0; a <= kBaysPerSide; ++a) {
                for (uint32_t b = 0; b < kBaysPerSide; ++b) {
                    out_.objects.push_back(
                        girder(meshes_, {u.x + line(b), beam_y, u.z + line(a)}, 0, bay_, bw, bd));
                    out_.objects.push_back(
                        girder(meshes_, {u.x + line(a), beam_y, u.z + line(b)}, 2, bay_, bw, bd));
                }
            }
            // Floors: always in the corridor (the walkway) below the roof, elsewhere at random,
            // never through a tank. Neighbouring slabs leave a 10 cm gap on the column lines.
            for (uint32_t j = 0; j < kBaysPerSide; ++j) {
                for (uint32_t i = 0; i < kBaysPerSide; ++i) {
                    const double chance = rng_.uniform();
                    const bool corridor = j == 1;
                    const bool wanted = corridor ? true : chance < (k == spec_.floors ? 0.7 : 0.5);
                    if (!wanted || tank_top[i + kBaysPerSide * j] > level(k) - 0.3) continue;
                    out_.objects.push_back(placeUnitBox(
                        meshes_.box, {u.x + line(i) + kSlabGap, level(k), u.z + line(j) + kSlabGap},
                        {u.x + line(i + 1) - kSlabGap, level(k) + kSlabThickness, u.z + line(j + 1) - kSlabGap}));
                }
            }
            // A bridge to the next unit's corridor on every storey below the roof, carried by
            // two beams continuing the corridor's column lines.
            if (bridge_to_next && k < spec_.floors) {
                const double x0 = u.x + s_, x1 = u.x + pitch_;
                out_.objects.push_back(placeUnitBox(
                    meshes_.box, {x0 + kSlabGap, level(k), u.z + line(1) + kSlabGap},
                    {x1 - kSlabGap, level(k) + kSlabThickness, u.z + line(2) - kSlabGap}));
                for (uint32_t a : {1u, 2u}) {
                    out_.objects.push_back(girder(meshes_, {x0, beam_y, u.z + line(a)}, 0, gap_, bw, bd));
                }
            }
        }
    }

    // A tank in side bay (i, j): a domed vertical cylinder, a sphere on four legs or a horizontal
    // cylinder on two saddles. Returns the height of its top.
    double addTank(const Unit& u, uint32_t i, uint32_t j, std::vector<glm::dvec3>& discs) {
        const double inner = bay_ - 2 * kClearOfColumn;  // clear width of the bay
        const double cx = u.x + line(i) + bay_ / 2, cz = u.z + line(j) + bay_ / 2;
        const double kind = rng_.uniform();
        const double size = rng_.uniform(0.35, 0.48);
        const uint32_t storeys = 1 + rng_.below(std::min(spec_.floors, 3u));
        if (kind < 0.5) {
            const double r = size * inner;
            const double wanted = storeys * hf_ - 1.0;  // cylinder plus dome
            const uint32_t ratio = std::clamp(static_cast<uint32_t>(std::lround(wanted / r - 1.0)), 1u, 8u);
            auto [it, added] = meshes_.domed.try_emplace(ratio, static_cast<uint32_t>(out_.meshes.size()));
            if (added) out_.meshes.push_back(domedTankMesh(ratio));
            PlacedObject tank;
            tank.mesh = it->second;
            tank.position = {cx, -kSink, cz};
            tank.linear = glm::mat3(static_cast<float>(r));
            out_.objects.push_back(tank);
            discs.push_back({cx - u.x, cz - u.z, r});
            return -kSink + r * (ratio + 1);
        }
        if (kind < 0.75) {
            const double r = size * inner, lift = 1.5;
            PlacedObject tank;
            tank.mesh = meshes_.sphere;
            tank.position = {cx, lift, cz};
            tank.linear = glm::mat3(static_cast<float>(r));
            out_.objects.push_back(tank);
            const double leg = 0.7 * r;
            for (double dx : {-leg, leg}) {
                for (double dz : {-leg, leg}) {
                    out_.objects.push_back(girder(meshes_, {cx + dx, -kSink, cz + dz}, 1, lift + r + kSink, 0.25f, 0.25f));
                }
            }
            discs.push_back({cx - u.x, cz - u.z, r});
            return lift + 2 * r;
        }
        const double r = std::min(1.3, 0.28 * inner), length = inner * rng_.uniform(0.8, 1.0);
        const double axis_y = r + 0.6;
        out_.objects.push_back(cylinder(meshes_.tank_cylinder, {cx - length / 2, axis_y, cz}, 0, length, r));
        for (double dx : {-0.3 * length, 0.3 * length}) {
            out_.objects.push_back(placeUnitBox(meshes_.box, {cx + dx - 0.15, -kSink, cz - 0.7 * r},
                                                {cx + dx + 0.15, axis_y, cz + 0.7 * r}));
        }
        discs.push_back({cx - u.x, cz - u.z, std::max(r, length / 2)});
        return axis_y + r;
    }

    void addPipe(const Unit& u, const std::vector<glm::dvec3>& tank_discs) {
        const double kind = rng_.uniform();
        const double radius = 0.08 + 0.37 * std::pow(rng_.uniform(), 2.0);
        const uint32_t storey = rng_.below(spec_.floors);
        const double floor = floorTop(storey);
        const double ceiling = level(storey + 1) - kBeamDepth + kBeamIntoSlab;  // underside of beams
        const double start = rng_.uniform(0.3, bay_), end = rng_.uniform(s_ - bay_, s_ - 0.3);
        const double low = rng_.uniform();
        double across = rng_.uniform(), along = rng_.uniform();
        // Along z it crosses the corridor, so it must clear the walkway's headroom.
        const double z_low = floor + kCorridorHeadroom + radius, z_high = ceiling - radius;
        if (kind < 0.3 && z_low < z_high) {
            const double x = bandAt(across, radius, false);
            out_.objects.push_back(cylinder(meshes_.pipe, {u.x + x, z_low + low * (z_high - z_low), u.z + start},
                                            2, end - start, radius));
        } else if (kind < 0.75) {
            const double y_low = floor + 0.6 + radius, y_high = ceiling - radius;
            const double y = y_low < y_high ? y_low + low * (y_high - y_low) : 0.5 * (floor + ceiling);
            const double z = bandAt(across, radius, true);
            out_.objects.push_back(cylinder(meshes_.pipe, {u.x + start, y, u.z + z}, 0, end - start, radius));
        } else {
            // Vertical: from the ground up through the storeys (the ones reaching the roof stand
            // above it), outside the corridor and clear of the tanks: a few tries, then none.
            const double y1 = storey + 1 == spec_.floors ? level(storey + 1) + 0.5 + 2.5 * low
                                                         : level(storey + 1) - kBeamDepth - 0.2;
            for (int attempt = 0; attempt < 8; ++attempt) {
                const glm::dvec2 at(bandAt(across, radius, false), bandAt(along, radius, true));
                bool clear = true;
                for (const glm::dvec3& t : tank_discs) {
                    if (glm::length(at - glm::dvec2(t.x, t.y)) < t.z + radius + 0.2) clear = false;
                }
                if (clear) {
                    out_.objects.push_back(cylinder(meshes_.pipe, {u.x + at.x, -kSink, u.z + at.y}, 1, y1 + kSink, radius));
                    break;
                }
                across = rng_.uniform();
                along = rng_.uniform();
            }
        }
    }

    // A local coordinate from u in [0, 1) inside one of the bands between column lines, `margin`
    // clear of the lines: any of the three bands, or only the two outside the corridor.
    double bandAt(double u, double margin, bool side_only) const {
        const uint32_t bands = side_only ? 2 : kBaysPerSide;
        const double scaled = u * bands;
        const auto index = std::min(static_cast<uint32_t>(scaled), bands - 1);
        const uint32_t band = side_only ? index * 2 : index;
        const double t = scaled - index;
        const double lo = line(band) + kClearOfColumn + margin, hi = line(band + 1) - kClearOfColumn - margin;
        return lo < hi ? lo + t * (hi - lo) : 0.5 * (lo + hi);
    }

    void addLanes(double width, double depth) {
        const double out_of_pad = 1.0 + (gap_ - 2.0) / 4.0;  // from a frame to its ring road
        for (uint32_t j = 0; j < spec_.units_z; ++j) {
            for (uint32_t i = 0; i < spec_.units_x; ++i) {
                const double x = i * pitch_, z = j * pitch_;
                out_.lanes.push_back(ring(x - out_of_pad, z - out_of_pad, x + s_ + out_of_pad, z + s_ + out_of_pad, 0.0));
            }
        }
        const double x0 = 0.6, x1 = width - 0.6;
        for (uint32_t j = 0; j < spec_.units_z; ++j) {
            const double mid = j * pitch_ + s_ / 2, half = s_ / 12;
            for (uint32_t k = 0; k < spec_.floors; ++k) {
                out_.lanes.push_back(ring(x0, mid - half, x1, mid + half, floorTop(k)));
                out_.lanes.push_back(ring(x0, mid - half, x1, mid + half, floorTop(k) + kFlierHeight));
                out_.lanes.push_back(ring(-out_of_pad, j * pitch_ - out_of_pad, width + out_of_pad,
                                          j * pitch_ + s_ + out_of_pad, level(k) + 3.0));
            }
        }
        out_.lanes.push_back(ring(-gap_ / 2, -gap_ / 2, width + gap_ / 2, depth + gap_ / 2, top_ + 8.0));
    }

    const PlantSpec& spec_;
    Rng rng_;
    SourceOutput out_;
    Meshes meshes_{};
    double s_ = 0, bay_ = 0, gap_ = 0, pitch_ = 0, hf_ = 0, top_ = 0;
    uint32_t tanks_dropped_ = 0;
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
