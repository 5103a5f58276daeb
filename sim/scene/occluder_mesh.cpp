// Inscribed occluder meshes: see occluder_mesh.h. meshoptimizer simplifies; everything that makes
// the result safe (welding, the closedness check, the inward step, the inside and gap checks) is
// here.
#include "sim/scene/occluder_mesh.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "sim/scene/outline_coverage.h"

namespace occsim {
namespace {

struct Welded {
    std::vector<glm::dvec3> positions;
    std::vector<uint32_t> indices;  // degenerate triangles (a repeated vertex) left out
};

// Vertices within `tolerance` of one another become one (a sphere's seam, computed twice, rarely
// lands on the same float); the welded surface is within `tolerance` of the mesh. A hole or slit
// narrower than the tolerance is closed by the weld (its walls become degenerate): the welded
// mesh serves the closedness and inside tests only, never the clearance check (prepareSolid).
Welded weld(const MeshData& mesh, double tolerance) {
    Welded w;
    std::map<std::tuple<int64_t, int64_t, int64_t>, std::vector<uint32_t>> cells;
    std::vector<uint32_t> remap(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::dvec3 p(mesh.positions[i]);
        const glm::dvec3 q = glm::floor(p / tolerance);
        const int64_t cx = static_cast<int64_t>(q.x), cy = static_cast<int64_t>(q.y),
                      cz = static_cast<int64_t>(q.z);
        uint32_t found = UINT32_MAX;
        for (int64_t dx = -1; dx <= 1 && found == UINT32_MAX; ++dx) {
            for (int64_t dy = -1; dy <= 1 && found == UINT32_MAX; ++dy) {
                for (int64_t dz = -1; dz <= 1 && found == UINT32_MAX; ++dz) {
                    const auto it = cells.find({cx + dx, cy + dy, cz + dz});
                    if (it == cells.end()) continue;
                    for (const uint32_t k : it->second) {
                        if (glm::length(w.positions[k] - p) <= tolerance) {
                            found = k;
                            break;
                        }
                    }
                }
            }
        }
        if (found == UINT32_MAX) {
            found = static_cast<uint32_t>(w.positions.size());
            w.positions.push_back(p);
            cells[{cx, cy, cz}].push_back(found);
        }
        remap[i] = found;
    }
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        if (i0 >= remap.size() || i1 >= remap.size() || i2 >= remap.size()) continue;
        const uint32_t a = remap[i0], b = remap[i1], c = remap[i2];
        if (a == b || b == c || a == c) continue;
        w.indices.insert(w.indices.end(), {a, b, c});
    }
    return w;
}

// Empty when every edge is used exactly once each way, else what is wrong.
std::string closedAndOriented(const std::vector<uint32_t>& indices) {
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t t = 0; t < indices.size(); t += 3) {
        for (int i = 0; i < 3; ++i) {
            const uint32_t p = indices[t + i], q = indices[t + (i + 1) % 3];
            if (++directed[{p, q}] > 1) return "the mesh is not consistently oriented";
        }
    }
    size_t open = 0;
    for (const auto& [edge, count] : directed) {
        if (!directed.count({edge.second, edge.first})) ++open;
    }
    if (open > 0) return "the mesh is not closed (" + std::to_string(open) + " open edges)";
    return {};
}

double signedVolume(const std::vector<glm::dvec3>& p, const std::vector<uint32_t>& idx) {
    double v = 0.0;
    for (size_t t = 0; t < idx.size(); t += 3) {
        v += glm::dot(p[idx[t]], glm::cross(p[idx[t + 1]], p[idx[t + 2]]));
    }
    return v / 6.0;
}

// Crossings of the ray from `o` along `d` with the mesh: the count, or -1 when the ray passes
// too near an edge or a vertex, or lies in a triangle's plane, to tell.
int crossings(const glm::dvec3& o, const glm::dvec3& d, const std::vector<glm::dvec3>& p,
              const std::vector<uint32_t>& idx) {
    constexpr double kGraze = 1e-9;
    int count = 0;
    for (size_t t = 0; t < idx.size(); t += 3) {
        const glm::dvec3 &a = p[idx[t]], &b = p[idx[t + 1]], &c = p[idx[t + 2]];
        const glm::dvec3 e1 = b - a, e2 = c - a;
        const glm::dvec3 h = glm::cross(d, e2);
        const double det = glm::dot(e1, h);
        const double scale = glm::length(e1) * glm::length(e2);
        if (std::abs(det) <= 1e-12 * scale) {
            // Parallel to the triangle's plane: a problem only when the ray lies in it.
            const glm::dvec3 n = glm::cross(e1, e2);
            if (std::abs(glm::dot(o - a, n)) <=
                kGraze * glm::length(n) * (1.0 + glm::length(o - a)))
                return -1;
            continue;
        }
        const double f = 1.0 / det;
        const glm::dvec3 s = o - a;
        const double u = f * glm::dot(s, h);
        const glm::dvec3 q = glm::cross(s, e1);
        const double v = f * glm::dot(d, q);
        const double dist = f * glm::dot(e2, q);
        if (u < -kGraze || v < -kGraze || u + v > 1.0 + kGraze) continue;  // clearly outside
        if (std::abs(dist) <= kGraze * (1.0 + glm::length(s))) return -1;  // starts on the surface
        if (dist < 0.0) continue;
        if (u <= kGraze || v <= kGraze || u + v >= 1.0 - kGraze) return -1;  // grazes an edge
        ++count;
    }
    return count;
}

// The interval of the triangle's vertices projected on `axis`.
std::pair<double, double> project(const glm::dvec3 (&t)[3], const glm::dvec3& axis) {
    const double a = glm::dot(t[0], axis), b = glm::dot(t[1], axis), c = glm::dot(t[2], axis);
    return {std::min({a, b, c}), std::max({a, b, c})};
}

}  // namespace

bool pointInsideClosedMesh(const glm::dvec3& point, const std::vector<glm::dvec3>& positions,
                           const std::vector<uint32_t>& welded) {
    // Three unrelated directions must each cross an odd number of times, cleanly.
    static const glm::dvec3 kDirections[3] = {glm::normalize(glm::dvec3(0.5773, 0.5822, 0.5721)),
                                              glm::normalize(glm::dvec3(-0.8124, 0.2431, 0.5301)),
                                              glm::normalize(glm::dvec3(0.1379, -0.9012, 0.4108))};
    for (const glm::dvec3& d : kDirections) {
        const int n = crossings(point, d, positions, welded);
        if (n < 0 || n % 2 == 0) return false;
    }
    return true;
}

bool trianglesWithinGap(const glm::dvec3 (&a)[3], const glm::dvec3 (&b)[3], double gap) {
    const glm::dvec3 ea[3] = {a[1] - a[0], a[2] - a[1], a[0] - a[2]};
    const glm::dvec3 eb[3] = {b[1] - b[0], b[2] - b[1], b[0] - b[2]};
    const glm::dvec3 na = glm::cross(ea[0], ea[1]), nb = glm::cross(eb[0], eb[1]);
    glm::dvec3 axes[17];
    int n = 0;
    axes[n++] = na;
    axes[n++] = nb;
    for (const glm::dvec3& x : ea) {
        for (const glm::dvec3& y : eb) axes[n++] = glm::cross(x, y);
    }
    for (int i = 0; i < 3; ++i) {
        axes[n++] = glm::cross(na, ea[i]);  // in-plane edge normals: coplanar pairs
        axes[n++] = glm::cross(nb, eb[i]);
    }
    for (const glm::dvec3& axis : axes) {
        const double len = glm::length(axis);
        if (!(len > 1e-300)) continue;
        const glm::dvec3 u = axis / len;
        const auto [a_lo, a_hi] = project(a, u);
        const auto [b_lo, b_hi] = project(b, u);
        if (a_hi + gap < b_lo || b_hi + gap < a_lo) return false;  // separated by more than gap
    }
    return true;
}

namespace {

// The object's solid as the checks need it: welded, closed and oriented (for the inside test), the
// room an occluder keeps from its surface, and the triangles as drawn (the float positions, not
// the welded ones, every triangle of nonzero extent) with their bounds, for the clearance check.
struct Solid {
    Welded w;
    std::vector<glm::dvec3> drawn;  // three corners a triangle
    double weld_tolerance = 0.0;
    double outward = 1.0;  // +1: counter-clockwise faces face out
    glm::dvec3 lo{INFINITY}, hi{-INFINITY};
    double size = 0.0;
    double gap = 0.0;
    std::vector<glm::dvec3> tri_lo, tri_hi;
    std::string refusal;  // why it is no solid; empty when it is one
};

Solid prepareSolid(const MeshData& source) {
    Solid s;
    const Aabb bounds = meshBounds(source);
    if (!isFiniteAndOrdered(bounds)) {
        s.refusal = "its vertices are not finite";
        return s;
    }
    // Weld what float rounding of one position computed twice can separate (a seam computed
    // twice through sin and cos, or through a deformation, lands a few to a dozen units in the
    // last place of the largest coordinate apart). Holes and slits narrower than this still
    // count: the clearance check below runs against the triangles as drawn.
    const double extent = glm::length(glm::dvec3(bounds.max) - glm::dvec3(bounds.min));
    s.weld_tolerance = std::max(1e-6 * extent, double(FLT_MIN));  // never 0: weld() divides
    s.w = weld(source, s.weld_tolerance);
    if (s.w.indices.empty()) {
        s.refusal = "no triangles with three distinct vertices";
        return s;
    }
    if (std::string problem = closedAndOriented(s.w.indices); !problem.empty()) {
        s.refusal = std::move(problem);
        return s;
    }
    const double volume = signedVolume(s.w.positions, s.w.indices);
    if (!(std::abs(volume) > 0.0) || !std::isfinite(volume)) {
        s.refusal = "the mesh encloses no volume";
        return s;
    }
    s.outward = volume > 0.0 ? 1.0 : -1.0;
    for (const glm::dvec3& p : s.w.positions) {
        s.lo = glm::min(s.lo, p);
        s.hi = glm::max(s.hi, p);
    }
    s.size = glm::length(s.hi - s.lo);
    // Room between the occluder and the surface: float rounding of the vertices (the result is
    // stored in float) and of the transforms, many times over.
    const double magnitude = std::max({std::abs(s.lo.x), std::abs(s.lo.y), std::abs(s.lo.z),
                                       std::abs(s.hi.x), std::abs(s.hi.y), std::abs(s.hi.z)});
    s.gap = std::max(1e-5 * s.size, 64.0 * FLT_EPSILON * magnitude) + 2.0 * s.weld_tolerance;
    // The clearance check runs against the triangles as drawn, those the weld made degenerate
    // included: the walls of a hole narrower than the weld are drawn, and an occluder crossing
    // them would cover what is seen through it. The weld moves no vertex by more than its
    // tolerance and the gap exceeds twice that, so an occluder clear of the drawn surface and
    // inside the welded solid is inside the drawn one.
    const size_t triangles = source.indices.size() / 3;
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t* idx = &source.indices[3 * t];
        if (idx[0] >= source.positions.size() || idx[1] >= source.positions.size() ||
            idx[2] >= source.positions.size()) {
            continue;
        }
        const glm::vec3 &a = source.positions[idx[0]], &b = source.positions[idx[1]],
                        &c = source.positions[idx[2]];
        if (a == b || b == c || a == c) continue;  // a point or a segment: draws nothing
        s.drawn.insert(s.drawn.end(), {glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)});
        s.tri_lo.push_back(glm::min(glm::dvec3(a), glm::min(glm::dvec3(b), glm::dvec3(c))));
        s.tri_hi.push_back(glm::max(glm::dvec3(a), glm::max(glm::dvec3(b), glm::dvec3(c))));
    }
    return s;
}

// Whether the triangle neither meets nor comes within the solid's gap of its drawn surface (its
// vertices' insideness is checked apart, once per vertex).
bool clearOfSurface(const Solid& s, const glm::dvec3 (&tri)[3]) {
    const glm::dvec3 t_lo = glm::min(tri[0], glm::min(tri[1], tri[2])) - s.gap;
    const glm::dvec3 t_hi = glm::max(tri[0], glm::max(tri[1], tri[2])) + s.gap;
    for (size_t t = 0; t < s.tri_lo.size(); ++t) {
        if (glm::any(glm::lessThan(s.tri_hi[t], t_lo)) ||
            glm::any(glm::greaterThan(s.tri_lo[t], t_hi))) {
            continue;
        }
        const glm::dvec3 other[3] = {s.drawn[3 * t], s.drawn[3 * t + 1], s.drawn[3 * t + 2]};
        if (trianglesWithinGap(tri, other, s.gap)) return false;
    }
    return true;
}

double triangleArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    return 0.5 * glm::length(glm::cross(b - a, c - a));
}

}  // namespace

OccluderMesh makeInscribedOccluder(const MeshData& source, const OccluderMeshSettings& settings) {
    OccluderMesh out;
    out.source_triangles = source.triangleCount();
    if (out.source_triangles < settings.min_triangles) {
        out.refusal = "too few triangles to gain from a simpler occluder (" +
                      std::to_string(out.source_triangles) + ")";
        return out;
    }
    if (out.source_triangles > settings.max_triangles) {
        out.refusal = "too many triangles to check an occluder against (" +
                      std::to_string(out.source_triangles) + ", at most " +
                      std::to_string(settings.max_triangles) + ")";
        return out;
    }
    const Solid solid = prepareSolid(source);
    if (!solid.refusal.empty()) {
        out.refusal = solid.refusal;
        return out;
    }
    const Welded& w = solid.w;

    // Simplify (meshoptimizer works in float).
    std::vector<float> flat(3 * w.positions.size());
    for (size_t i = 0; i < w.positions.size(); ++i) {
        for (int k = 0; k < 3; ++k) flat[3 * i + k] = static_cast<float>(w.positions[i][k]);
    }
    const size_t target =
        std::max<size_t>(3 * 4, 3 * static_cast<size_t>(settings.triangle_share *
                                                        static_cast<double>(w.indices.size() / 3)));
    std::vector<uint32_t> simple(w.indices.size());
    float error = 0.0f;
    simple.resize(meshopt_simplify(simple.data(), w.indices.data(), w.indices.size(), flat.data(),
                                   w.positions.size(), 3 * sizeof(float), target, 0.05f, 0,
                                   &error));
    if (simple.size() < 3 || simple.size() >= w.indices.size()) {
        out.refusal = "meshoptimizer could not simplify it";
        return out;
    }

    // Vertex normals of the simplified surface, outward, area-weighted.
    std::vector<glm::dvec3> normals(w.positions.size(), glm::dvec3(0.0));
    for (size_t t = 0; t < simple.size(); t += 3) {
        const glm::dvec3 &a = w.positions[simple[t]], &b = w.positions[simple[t + 1]],
                         &c = w.positions[simple[t + 2]];
        const glm::dvec3 n = solid.outward * glm::cross(b - a, c - a);
        for (int i = 0; i < 3; ++i) normals[simple[t + i]] += n;
    }
    double total_area = 0.0;
    for (size_t t = 0; t < simple.size(); t += 3) {
        total_area += triangleArea(w.positions[simple[t]], w.positions[simple[t + 1]],
                                   w.positions[simple[t + 2]]);
    }

    // The step: the smallest that keeps `kept_area_share` of the area and `min_outline_share` of
    // the outline from every side; else, of those keeping that outline, the one keeping the most
    // area; else none. (Before the outline was weighed the first rule was area alone: where that
    // step keeps the outline too, the choice is the same.)
    const ObjectOutlines outlines(w.positions, w.indices, settings.outline_resolution);
    std::vector<uint32_t> best;
    std::vector<glm::dvec3> best_positions;
    double best_area = 0.0, best_step = 0.0;
    OutlineShare best_share{0.0, "x"}, most_outline{0.0, "x"};
    double most_outline_step = 0.0;
    bool any_kept = false;
    for (const double step_share : {0.0, 0.002, 0.005, 0.01, 0.02, 0.04, 0.08}) {
        const double step = step_share * solid.size;
        std::vector<glm::dvec3> moved(w.positions.size());
        std::vector<int8_t> inside(w.positions.size(), -1);  // -1: not yet checked
        for (size_t i = 0; i < w.positions.size(); ++i) {
            const double len = glm::length(normals[i]);
            moved[i] = len > 0.0 ? w.positions[i] - (step / len) * normals[i] : w.positions[i];
        }
        std::vector<uint32_t> kept;
        double area = 0.0;
        for (size_t t = 0; t < simple.size(); t += 3) {
            bool ok = true;
            for (int i = 0; i < 3 && ok; ++i) {
                int8_t& in = inside[simple[t + i]];
                if (in < 0)
                    in = pointInsideClosedMesh(moved[simple[t + i]], w.positions, w.indices);
                ok = in == 1;
            }
            if (!ok) continue;
            const glm::dvec3 tri[3] = {moved[simple[t]], moved[simple[t + 1]],
                                       moved[simple[t + 2]]};
            if (!clearOfSurface(solid, tri)) continue;
            kept.insert(kept.end(), {simple[t], simple[t + 1], simple[t + 2]});
            area += triangleArea(tri[0], tri[1], tri[2]);
        }
        if (kept.empty()) continue;
        any_kept = true;
        const OutlineShare share = outlines.worst(moved, kept);
        if (share.share > most_outline.share) {
            most_outline = share;
            most_outline_step = step;
        }
        if (share.share < settings.min_outline_share || area <= best_area) continue;
        best_area = area;
        best = std::move(kept);
        best_positions = std::move(moved);
        best_step = step;
        best_share = share;
        if (best_area >= settings.kept_area_share * total_area) break;
    }
    if (!any_kept) {
        out.refusal = "no triangle of the simplified mesh could be made to lie inside it";
        return out;
    }
    if (best.empty()) {
        out.outline_share = most_outline.share;
        char line[240];
        std::snprintf(line, sizeof line,
                      "the occluder it could make covers at most %.0f %% of its outline seen along "
                      "%s (inward step %.3g m; parts thinner than twice the step vanish)",
                      100.0 * most_outline.share, most_outline.side, most_outline_step);
        out.refusal = line;
        return out;
    }
    out.outline_share = best_share.share;

    // Compact: only the vertices the kept triangles use, back in float. Rounding to float moves a
    // vertex by far less than the gap the checks kept.
    std::vector<uint32_t> remap(best_positions.size(), UINT32_MAX);
    for (uint32_t& i : best) {
        if (remap[i] == UINT32_MAX) {
            remap[i] = static_cast<uint32_t>(out.mesh.positions.size());
            out.mesh.positions.emplace_back(best_positions[i]);
            const double len = glm::length(normals[i]);
            out.mesh.normals.emplace_back(len > 0.0 ? glm::vec3(normals[i] / len)
                                                    : glm::vec3(0, 1, 0));
        }
        i = remap[i];
    }
    out.mesh.indices = std::move(best);
    if (solid.outward < 0.0) {
        for (size_t t = 0; t < out.mesh.indices.size(); t += 3) {
            std::swap(out.mesh.indices[t + 1], out.mesh.indices[t + 2]);
        }
    }
    out.inward_step_m = best_step;
    out.kept_area_share = best_area / total_area;
    return out;
}

OccluderMesh checkAuthoredOccluder(const MeshData& object, const MeshData& occluder,
                                   const OccluderMeshSettings& settings) {
    OccluderMesh out;
    out.source_triangles = object.triangleCount();
    if (out.source_triangles > settings.max_triangles) {
        out.refusal = "its object's mesh has too many triangles to check it against (" +
                      std::to_string(out.source_triangles) + ", at most " +
                      std::to_string(settings.max_triangles) + ")";
        return out;
    }
    const Solid solid = prepareSolid(object);
    if (!solid.refusal.empty()) {
        out.refusal = "its object's mesh encloses no solid to check it against: " + solid.refusal;
        return out;
    }
    // Checking costs the product of both meshes' triangles; an occluder with more triangles than
    // its object would also cost masked more than the object's own mesh. So the object's mesh cap
    // bounds both, and a million-triangle occluder is refused before a single check.
    if (occluder.triangleCount() > out.source_triangles) {
        out.refusal = "it has more triangles (" + std::to_string(occluder.triangleCount()) +
                      ") than its object's mesh (" + std::to_string(out.source_triangles) +
                      "): masked would rasterise more than the object itself";
        return out;
    }
    const size_t triangles = occluder.indices.size() / 3;
    std::vector<int8_t> inside(occluder.positions.size(), -1);  // -1: not yet checked
    std::vector<uint32_t> remap(occluder.positions.size(), UINT32_MAX);
    double total_area = 0.0, kept_area = 0.0;
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t* idx = &occluder.indices[3 * t];
        if (idx[0] >= occluder.positions.size() || idx[1] >= occluder.positions.size() ||
            idx[2] >= occluder.positions.size()) {
            continue;
        }
        const glm::dvec3 tri[3] = {glm::dvec3(occluder.positions[idx[0]]),
                                   glm::dvec3(occluder.positions[idx[1]]),
                                   glm::dvec3(occluder.positions[idx[2]])};
        const double area = triangleArea(tri[0], tri[1], tri[2]);
        if (!std::isfinite(area)) continue;
        total_area += area;
        bool ok = true;
        for (int i = 0; i < 3 && ok; ++i) {
            int8_t& in = inside[idx[i]];
            if (in < 0) in = pointInsideClosedMesh(tri[i], solid.w.positions, solid.w.indices);
            ok = in == 1;
        }
        if (!ok || !clearOfSurface(solid, tri)) continue;
        kept_area += area;
        for (int i = 0; i < 3; ++i) {
            if (remap[idx[i]] == UINT32_MAX) {
                remap[idx[i]] = static_cast<uint32_t>(out.mesh.positions.size());
                out.mesh.positions.push_back(occluder.positions[idx[i]]);
                out.mesh.normals.push_back(idx[i] < occluder.normals.size()
                                               ? occluder.normals[idx[i]]
                                               : glm::vec3(0, 1, 0));
            }
            out.mesh.indices.push_back(remap[idx[i]]);
        }
    }
    out.dropped_triangles = static_cast<uint32_t>(triangles - out.mesh.indices.size() / 3);
    out.kept_area_share = total_area > 0.0 ? kept_area / total_area : 0.0;
    if (out.mesh.indices.empty()) {
        out.refusal =
            "none of its " + std::to_string(triangles) + " triangles lies inside its object";
    }
    return out;
}

}  // namespace occsim
