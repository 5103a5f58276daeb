// City: the urban walkthrough of the CHC paper (Bittner, Wimmer, Piringer, Purgathofer 2004), "a
// classical target for occlusion culling": from the streets the buildings hide most of the city,
// and from above the roofs almost nothing is hidden. There is no geometry inside the buildings.
//
// Layout (metres, y up). pitch = block_size + street_width. Street centre lines run along
// x = i * pitch (i = 0..blocks_x) and z = j * pitch (j = 0..blocks_z); block (i, j) is the square
// between them, x in [i * pitch + street_width / 2, (i + 1) * pitch - street_width / 2] (the same
// in z). The street surface is y = 0, the city spans x in [-street_width / 2,
// blocks_x * pitch + street_width / 2].
//
// Objects, in this order: a bedrock slab under everything (what the cracks between slabs show),
// one street slab per street line along x (spanning the city), one per street segment along z
// between two crossings, one raised pavement per block, and the buildings of each block. Every
// building is its own object, so the BSP tree and the cullers can cull them one by one; buildings
// share meshes by archetype (storeys and window columns per side), stretched to their exact size
// through `linear`.
//
// No two objects touch: neighbouring slabs leave 1 cm cracks and buildings float 1 cm above their
// pavement. Where two objects touch or cut into each other, their depths are equal along the
// contact line, and a pixel there whose depths tie exactly shows whichever object was drawn
// first; the cullers draw in another order than the ground truth, so such a pixel would count as
// an error that no culling decision caused.
//
// Lanes: ring roads for cars, 2 cm above the street surface (a mover's base rests on the lane
// point, and floats clear of the street for the same reason), a quarter street width from the
// centre line on the block's side, driven clockwise seen from above (right-hand traffic keeps the
// block on its right). One ring runs round each row of blocks (along the streets z = const) and
// one round each column of blocks (along the streets x = const); rows close their ends on the
// outer side of the boundary streets in x, columns on the outer side of those in z, so no two
// rings share a stretch of lane.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include "occsim/culling/geometry/random.h"
#include "sim/scene/generators.h"
#include "sim/scene/primitives.h"

namespace occsim {
namespace {

constexpr double kStoreyM = 3.5;        // floor-to-floor height of a building
constexpr double kBayM = 3.2;           // window spacing along a facade
constexpr double kPavementTopM = 0.15;  // kerb height of the block pavements
constexpr double kSlabDepthM = 0.3;     // street and pavement slabs reach down to -0.3
constexpr double kBedrockTopM = -0.4;
constexpr double kCrackM = 0.01;  // between neighbouring objects, which never touch
constexpr double kLaneHeightM = 0.02;
constexpr double kMinBuildingSideM = 4.0;
constexpr double kEmptyLotChance = 0.06;  // a few lots stay empty (squares, car parks)
constexpr double kTowerChance = 0.08;

// A building archetype: storeys and window columns on the x and z facades. Its mesh is built at
// the nominal size (columns * kBayM by storeys * kStoreyM) and stretched to each building's size,
// which is within about a quarter of the nominal one, so windows keep their proportions.
struct Archetype {
    uint32_t storeys = 0;
    uint32_t columns_x = 0;  // windows along the x extent (on the +-z facades)
    uint32_t columns_z = 0;  // windows along the z extent (on the +-x facades)
    auto key() const { return std::tie(storeys, columns_x, columns_z); }
    bool operator<(const Archetype& o) const { return key() < o.key(); }
};

glm::vec3 nominalSize(const Archetype& a) {
    return glm::vec3(static_cast<float>(a.columns_x * kBayM),
                     static_cast<float>(a.storeys * kStoreyM),
                     static_cast<float>(a.columns_z * kBayM));
}

// The building of an archetype, standing on y = 0 centred in x and z: a body, one protruding
// window box per storey and bay on every facade (the detail a culler saves by not drawing it), a
// cornice, a parapet ring and a roof housing; towers (12 storeys or more) get an antenna mast.
MeshData buildingMesh(const Archetype& a) {
    const glm::vec3 size = nominalSize(a);
    const float w = size.x / 2, h = size.y, d = size.z / 2;
    MeshData m;
    appendBox(m, {-w, 0, -d}, {w, h, d});
    const float out = 0.12f, in = 0.10f;      // window boxes straddle the facade
    const float win_w = 0.75f, win_h = 0.8f;  // half sizes: 1.5 m x 1.6 m windows
    for (uint32_t s = 0; s < a.storeys; ++s) {
        const float y = static_cast<float>(s * kStoreyM) + 0.9f + win_h;
        for (uint32_t c = 0; c < a.columns_x; ++c) {  // facades facing +z and -z
            const float x = -w + static_cast<float>((c + 0.5) * kBayM);
            appendBox(m, {x - win_w, y - win_h, d - in}, {x + win_w, y + win_h, d + out});
            appendBox(m, {x - win_w, y - win_h, -d - out}, {x + win_w, y + win_h, -d + in});
        }
        for (uint32_t c = 0; c < a.columns_z; ++c) {  // facades facing +x and -x
            const float z = -d + static_cast<float>((c + 0.5) * kBayM);
            appendBox(m, {w - in, y - win_h, z - win_w}, {w + out, y + win_h, z + win_w});
            appendBox(m, {-w - out, y - win_h, z - win_w}, {-w + in, y + win_h, z + win_w});
        }
    }
    // Cornice: a slab overhanging the facades just below the roof line.
    appendBox(m, {-w - 0.2f, h - 0.5f, -d - 0.2f}, {w + 0.2f, h - 0.1f, d + 0.2f});
    // Parapet: four walls along the roof edge (their corners overlap inside the same mesh).
    const float t = 0.3f, p = 1.0f;
    appendBox(m, {-w, h, -d}, {w, h + p, -d + t});
    appendBox(m, {-w, h, d - t}, {w, h + p, d});
    appendBox(m, {-w, h, -d}, {-w + t, h + p, d});
    appendBox(m, {w - t, h, -d}, {w, h + p, d});
    // Roof housing (stairs, lift machinery), off centre so that roofs do not all look alike.
    const float side = (a.storeys + a.columns_x) % 2 == 0 ? 1.0f : -1.0f;
    appendBox(m, {side * w * 0.1f - w * 0.3f, h, -d * 0.5f},
              {side * w * 0.1f + w * 0.3f, h + 3.0f, d * 0.1f});
    if (a.storeys >= 12)
        appendBox(m, {-0.2f, h, d * 0.4f - 0.2f}, {0.2f, h + 10.0f, d * 0.4f + 0.2f});
    return m;
}

struct Rect {
    double x0, z0, x1, z1;
    double width() const { return x1 - x0; }
    double depth() const { return z1 - z0; }
};

// Cuts a block into `n` lots by recursive halving across the longer side, at a jittered share
// proportional to the lots on each side, so footprints vary but stay roughly even.
void splitLots(const Rect& r, uint32_t n, Rng& rng, std::vector<Rect>& lots) {
    if (n <= 1) {
        lots.push_back(r);
        return;
    }
    const uint32_t first = n / 2;
    const double share =
        std::clamp(static_cast<double>(first) / n + rng.uniform(-0.1, 0.1), 0.25, 0.75);
    if (r.width() >= r.depth()) {
        const double x = r.x0 + share * r.width();
        splitLots({r.x0, r.z0, x, r.z1}, first, rng, lots);
        splitLots({x, r.z0, r.x1, r.z1}, n - first, rng, lots);
    } else {
        const double z = r.z0 + share * r.depth();
        splitLots({r.x0, r.z0, r.x1, z}, first, rng, lots);
        splitLots({r.x0, z, r.x1, r.z1}, n - first, rng, lots);
    }
}

// Most buildings stay in the lower half of the height range; a few towers reach its top.
double buildingHeight(const CitySpec& spec, Rng& rng) {
    const double range = spec.height_max_m - spec.height_min_m;
    if (rng.uniform() < kTowerChance) return spec.height_min_m + range * rng.uniform(0.7, 1.0);
    const double u = rng.uniform();
    return spec.height_min_m + range * 0.55 * u * std::sqrt(u);
}

// Storeys and window columns of an archetype. Small counts stay exact; larger ones snap to steps
// of about 20 %, so that buildings of similar size share an archetype and its mesh (their windows
// stretch by at most 10 %).
uint32_t archetypeCount(double length, double unit, uint32_t lo) {
    const double n = std::max(static_cast<double>(lo), length / unit);
    if (n < 6.5) return static_cast<uint32_t>(std::lround(n));
    const double step = std::log(1.2);
    return static_cast<uint32_t>(
        std::lround(6.0 * std::exp(std::round(std::log(n / 6.0) / step) * step)));
}

// A closed rectangle at height y, clockwise seen from above (y up, so +z points down the page).
std::vector<glm::dvec3> ring(double x0, double z0, double x1, double z1, double y) {
    return {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};
}

// The street grid's measures: street width, half of it, block pitch, and the city's extent.
struct CityGrid {
    explicit CityGrid(const CitySpec& spec)
        : street(spec.street_width_m),
          half(spec.street_width_m / 2),
          pitch(spec.block_size_m + spec.street_width_m),
          width(spec.blocks_x * pitch),
          depth(spec.blocks_z * pitch) {}
    double street, half, pitch, width, depth;
};

constexpr uint32_t kCityUnitBox = 0;  // the mesh every slab and street is a scaled copy of

// The bedrock under everything, and the streets: along x at full length, crossings included;
// along z one segment between each pair of crossings.
void addGroundAndStreets(const CitySpec& spec, const CityGrid& g, SourceOutput& out) {
    out.objects.push_back(placeUnitBox(kCityUnitBox, {-g.half, kBedrockTopM - 1.0, -g.half},
                                       {g.width + g.half, kBedrockTopM, g.depth + g.half}));
    for (uint32_t j = 0; j <= spec.blocks_z; ++j) {
        const double z = j * g.pitch;
        out.objects.push_back(placeUnitBox(kCityUnitBox, {-g.half, -kSlabDepthM, z - g.half},
                                           {g.width + g.half, 0.0, z + g.half}));
    }
    for (uint32_t i = 0; i <= spec.blocks_x; ++i) {
        const double x = i * g.pitch;
        for (uint32_t j = 0; j < spec.blocks_z; ++j) {
            out.objects.push_back(placeUnitBox(
                kCityUnitBox, {x - g.half, -kSlabDepthM, j * g.pitch + g.half + kCrackM},
                {x + g.half, 0.0, (j + 1) * g.pitch - g.half - kCrackM}));
        }
    }
}

// The building on a lot's footprint `f` (setbacks applied), `height` metres tall, with the mesh
// of its archetype (made on first use).
PlacedObject placeBuilding(const Rect& f, double height,
                           std::map<Archetype, uint32_t>& archetype_mesh, SourceOutput& out) {
    // Archetypes are wider in x than in z; a building deeper than wide uses one turned a quarter
    // about y, so both orientations share a mesh.
    const bool turned = f.depth() > f.width();
    const double along = turned ? f.depth() : f.width();
    const double across = turned ? f.width() : f.depth();
    const double base = kPavementTopM + kCrackM;
    const Archetype a{archetypeCount(height - base, kStoreyM, 2), archetypeCount(along, kBayM, 1),
                      archetypeCount(across, kBayM, 1)};
    auto [it, added] = archetype_mesh.try_emplace(a, static_cast<uint32_t>(out.meshes.size()));
    if (added) out.meshes.push_back(buildingMesh(a));
    const glm::vec3 nominal = nominalSize(a);
    PlacedObject building;
    building.mesh = it->second;
    building.position = {0.5 * (f.x0 + f.x1), base, 0.5 * (f.z0 + f.z1)};
    building.linear = scaleMatrix(glm::vec3(static_cast<float>(along / nominal.x),
                                            static_cast<float>((height - base) / nominal.y),
                                            static_cast<float>(across / nominal.z)));
    // A quarter turn about y: x -> -z, z -> x (determinant +1, faces stay outward).
    if (turned) building.linear = glm::mat3(0, 0, -1, 0, 1, 0, 1, 0, 0) * building.linear;
    return building;
}

// Block (i, j): its pavement slab, then its lots, most with a building.
void addBlock(const CitySpec& spec, const CityGrid& g, uint32_t i, uint32_t j, Rng& rng,
              std::map<Archetype, uint32_t>& archetype_mesh, uint32_t& small_lots,
              SourceOutput& out) {
    const Rect block{i * g.pitch + g.half, j * g.pitch + g.half, (i + 1) * g.pitch - g.half,
                     (j + 1) * g.pitch - g.half};
    out.objects.push_back(placeUnitBox(kCityUnitBox,
                                       {block.x0 + kCrackM, -kSlabDepthM, block.z0 + kCrackM},
                                       {block.x1 - kCrackM, kPavementTopM, block.z1 - kCrackM}));
    std::vector<Rect> lots;
    splitLots(block, spec.buildings_per_block, rng, lots);
    for (const Rect& lot : lots) {
        // Draw every random number of a lot whether or not it gets a building, so that one lot's
        // outcome does not shift the next lot's layout.
        const double empty = rng.uniform();
        const double height = buildingHeight(spec, rng);
        const double setback[4] = {rng.uniform(0.8, 2.5), rng.uniform(0.8, 2.5),
                                   rng.uniform(0.8, 2.5), rng.uniform(0.8, 2.5)};
        if (empty < kEmptyLotChance) continue;
        // Setbacks shrink so a building keeps about 60 % of its lot, but stay wider than the
        // cornice and windows reach out, so that neighbours never touch.
        const double kx = std::min(1.0, 0.4 * lot.width() / (setback[0] + setback[1]));
        const double kz = std::min(1.0, 0.4 * lot.depth() / (setback[2] + setback[3]));
        const auto back = [](double k, double b) { return std::max(0.5, k * b); };
        const Rect f{lot.x0 + back(kx, setback[0]), lot.z0 + back(kz, setback[2]),
                     lot.x1 - back(kx, setback[1]), lot.z1 - back(kz, setback[3])};
        if (f.width() < kMinBuildingSideM || f.depth() < kMinBuildingSideM) {
            ++small_lots;
            continue;
        }
        out.objects.push_back(placeBuilding(f, height, archetype_mesh, out));
    }
}

// Ring roads, a quarter street width inside the ring's own side of each street: around each row
// of blocks, then around each column.
void addRingRoads(const CitySpec& spec, const CityGrid& g, SourceOutput& out) {
    const double lane = g.street / 4, y = kLaneHeightM;
    for (uint32_t j = 0; j < spec.blocks_z; ++j) {
        out.lanes.push_back(
            ring(-lane, j * g.pitch + lane, g.width + lane, (j + 1) * g.pitch - lane, y));
    }
    for (uint32_t i = 0; i < spec.blocks_x; ++i) {
        out.lanes.push_back(
            ring(i * g.pitch + lane, -lane, (i + 1) * g.pitch - lane, g.depth + lane, y));
    }
}

}  // namespace

SourceOutput generateCity(const CitySpec& spec, uint64_t seed) {
    if (spec.blocks_x == 0 || spec.blocks_z == 0 || !(spec.block_size_m > 0) ||
        !(spec.street_width_m > 0) || !(spec.height_min_m > 0) ||
        spec.height_min_m > spec.height_max_m || spec.buildings_per_block == 0) {
        throw std::invalid_argument("generateCity: invalid spec");
    }
    SourceOutput out;
    Rng rng(seed);
    const CityGrid grid(spec);
    out.meshes.push_back(makeBox(glm::vec3(1.0f)));  // the unit box, mesh 0
    addGroundAndStreets(spec, grid, out);
    std::map<Archetype, uint32_t> archetype_mesh;
    uint32_t small_lots = 0;
    for (uint32_t j = 0; j < spec.blocks_z; ++j) {
        for (uint32_t i = 0; i < spec.blocks_x; ++i) {
            addBlock(spec, grid, i, j, rng, archetype_mesh, small_lots, out);
        }
    }
    if (small_lots > 0) {
        out.warnings.push_back("city: " + std::to_string(small_lots) +
                               " lots were too small for a building (fewer buildings_per_block or "
                               "a larger block_size fills them)");
    }
    addRingRoads(spec, grid, out);
    out.region = sourceBounds(out);
    return out;
}

}  // namespace occsim
