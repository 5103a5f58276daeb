// The plant's equipment: tanks in the side bays and pipes threaded clear of them and of each
// other (plant.cpp describes the layout).
#include <algorithm>
#include <cmath>

#include "sim/scene/plant_parts.h"
#include "sim/scene/primitives.h"

namespace occsim::plant_detail {
namespace {

Aabb objectBox(const PlantContext& c, const PlacedObject& o) {
    glm::mat4 m(o.linear);
    m[3] = glm::vec4(0, 0, 0, 1);
    Aabb box = transformAabb(meshBounds(c.out.meshes[o.mesh]), m);
    return {glm::vec3(glm::dvec3(box.min) + o.position),
            glm::vec3(glm::dvec3(box.max) + o.position)};
}

// A local coordinate from u in [0, 1) inside one of the bands between column lines, `margin`
// clear of the lines: any of the three bands, or only the two outside the corridor.
double bandAt(const PlantContext& c, double u, double margin, bool side_only) {
    const uint32_t bands = side_only ? 2 : kBaysPerSide;
    const double scaled = u * bands;
    const auto index = std::min(static_cast<uint32_t>(scaled), bands - 1);
    const uint32_t band = side_only ? index * 2 : index;
    const double t = scaled - index;
    const double lo = c.line(band) + kClearOfColumn + margin,
                 hi = c.line(band + 1) - kClearOfColumn - margin;
    return lo < hi ? lo + t * (hi - lo) : 0.5 * (lo + hi);
}

}  // namespace

double addTank(PlantContext& c, const Unit& u, uint32_t i, uint32_t j, std::vector<Aabb>& taken) {
    const double inner = c.bay - 2 * kClearOfColumn;  // clear width of the bay
    const double cx = u.x + c.line(i) + c.bay / 2, cz = u.z + c.line(j) + c.bay / 2;
    const double kind = c.rng.uniform();
    const double size = c.rng.uniform(0.35, 0.48);
    const uint32_t storeys = 1 + c.rng.below(std::min(c.spec.floors, 3u));
    const size_t first = c.out.objects.size();
    double top = 0.0;
    if (kind < 0.5) {
        const double r = size * inner;
        const double wanted = storeys * c.hf - 1.0;  // cylinder plus dome
        const auto ratio = static_cast<uint32_t>(std::clamp(std::lround(wanted / r - 1.0), 1L, 8L));
        auto [it, added] =
            c.meshes.domed.try_emplace(ratio, static_cast<uint32_t>(c.out.meshes.size()));
        if (added) c.out.meshes.push_back(domedTankMesh(ratio));
        PlacedObject tank;
        tank.mesh = it->second;
        tank.position = {cx, kCrack, cz};
        tank.linear = glm::mat3(static_cast<float>(r));
        c.out.objects.push_back(tank);
        top = kCrack + r * (ratio + 1);
    } else if (kind < 0.75) {
        const double r = size * inner, lift = 1.5, centre = lift + r;
        PlacedObject tank;
        tank.mesh = c.meshes.sphere;
        tank.position = {cx, lift, cz};
        tank.linear = glm::mat3(static_cast<float>(r));
        c.out.objects.push_back(tank);
        // Legs end 1 cm below the sphere, measured at their corner nearest its axis (the
        // tessellated sphere lies inside the true one, so it clears the mesh too).
        const double leg = 0.7 * r, half = 0.125;
        const double nearest = std::sqrt(2.0) * (leg - half);
        const double leg_top = centre - std::sqrt(r * r - nearest * nearest) - kCrack;
        for (double dx : {-leg, leg}) {
            for (double dz : {-leg, leg}) {
                c.out.objects.push_back(girder(c.meshes.ibeam, {cx + dx, kCrack, cz + dz}, 1,
                                               leg_top - kCrack, 2 * half, 2 * half));
            }
        }
        top = lift + 2 * r;
    } else {
        const double r = std::min(1.3, 0.28 * inner), length = inner * c.rng.uniform(0.8, 1.0);
        const double axis_y = r + 0.6;
        c.out.objects.push_back(
            cylinder(c.meshes.tank_cylinder, {cx - length / 2, axis_y, cz}, 0, length, r));
        for (double dx : {-0.3 * length, 0.3 * length}) {
            c.out.objects.push_back(
                placeUnitBox(c.meshes.box, {cx + dx - 0.15, kCrack, cz - 0.7 * r},
                             {cx + dx + 0.15, axis_y - r - kCrack, cz + 0.7 * r}));
        }
        top = axis_y + r;
    }
    Aabb box;
    for (size_t o = first; o < c.out.objects.size(); ++o)
        extend(box, objectBox(c, c.out.objects[o]));
    taken.push_back({box.min - glm::vec3(kCrack), box.max + glm::vec3(kCrack)});
    return top;
}

void addPipe(PlantContext& c, const Unit& u, std::vector<Aabb>& taken) {
    for (int attempt = 0; attempt < kPipeTries; ++attempt) {
        const double kind = c.rng.uniform();
        const double r = 0.08 + 0.37 * std::pow(c.rng.uniform(), 2.0);
        const uint32_t storey = c.rng.below(c.spec.floors);
        const double a = c.rng.uniform(), b = c.rng.uniform(), rise = c.rng.uniform();
        const double start = c.rng.uniform(0.3, c.bay), end = c.rng.uniform(c.s - c.bay, c.s - 0.3);
        const double floor = c.floorTop(storey), ceiling = c.beamBottom(storey + 1) - kCrack;
        const double z_low = floor + kCorridorHeadroom + r, z_high = ceiling - r;
        const double x_low = floor + 0.6 + r, x_high = ceiling - r;
        glm::dvec3 from;
        int axis = 0;
        double length = 0.0;
        if (kind < 0.3 && z_low < z_high) {  // along z, crossing the corridor overhead
            from = {u.x + bandAt(c, a, r, false), z_low + b * (z_high - z_low), u.z + start};
            axis = 2;
            length = end - start;
        } else if (kind < 0.75 && x_low < x_high) {  // along x, beside the corridor
            from = {u.x + start, x_low + b * (x_high - x_low), u.z + bandAt(c, a, r, true)};
            axis = 0;
            length = end - start;
        } else {
            // A riser just outside the frame, from the pad up through one or more storeys
            // (those reaching the roof stand above it); on the sides facing the bridges, clear
            // of the corridor.
            const auto side = static_cast<uint32_t>(a * 4) % 4;
            const double out = 0.3 + r;  // clear of the columns and outer beams
            double along = 0.3 + b * (c.s - 0.6);
            if (side < 2 && along > c.line(1) - out - 0.2 && along < c.line(2) + out + 0.2) {
                along = along < c.s / 2 ? c.line(1) - out - 0.2 : c.line(2) + out + 0.2;
            }
            const double across = side % 2 == 0 ? -out : c.s + out;
            from = side < 2 ? glm::dvec3(u.x + across, kCrack, u.z + along)
                            : glm::dvec3(u.x + along, kCrack, u.z + across);
            axis = 1;
            const uint32_t up = storey + 1;
            length = (up == c.spec.floors ? c.top + 0.5 + 2.5 * rise : c.beamBottom(up)) - kCrack;
        }
        const Aabb box = cylinderBox(from, axis, length, r);
        if (overlapsAny(box, taken)) continue;
        c.out.objects.push_back(cylinder(c.meshes.pipe, from, axis, length, r));
        taken.push_back({box.min - glm::vec3(kCrack), box.max + glm::vec3(kCrack)});
        return;
    }
    ++c.pipes_dropped;
}

}  // namespace occsim::plant_detail
