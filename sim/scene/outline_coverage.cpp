#include "sim/scene/outline_coverage.h"

#include <algorithm>
#include <cmath>

namespace occsim {
namespace {

constexpr struct {
    glm::dvec3 direction;
    const char* name;
} kSides[7] = {{{1, 0, 0}, "x"},          {{0, 1, 0}, "y"},           {{0, 0, 1}, "z"},
               {{1, 1, 1}, "(1, 1, 1)"},  {{1, 1, -1}, "(1, 1, -1)"}, {{1, -1, 1}, "(1, -1, 1)"},
               {{-1, 1, 1}, "(-1, 1, 1)"}};

glm::dvec2 project(const ObjectOutlines::Side& s, const glm::dvec3& p) {
    return {glm::dot(p, s.u), glm::dot(p, s.v)};
}

// Marks the cells whose centre the triangle covers (either winding; edges included).
void draw(const ObjectOutlines::Side& s, uint32_t n, const glm::dvec2& a, const glm::dvec2& b,
          const glm::dvec2& c, std::vector<uint8_t>& cells) {
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (!(std::abs(area) > 0.0)) return;  // edge-on: covers no area
    const glm::dvec2 t_lo = glm::min(a, glm::min(b, c)), t_hi = glm::max(a, glm::max(b, c));
    // Cell k's centre is at lo + (k + 0.5) cell: the first and last centres inside the bounds.
    const auto first = [](double v, double lo, double cell) {
        return static_cast<int64_t>(std::ceil((v - lo) / cell - 0.5));
    };
    const auto last = [](double v, double lo, double cell) {
        return static_cast<int64_t>(std::floor((v - lo) / cell - 0.5));
    };
    const auto top = static_cast<int64_t>(n) - 1;
    const int64_t x0 = std::max<int64_t>(0, first(t_lo.x, s.lo.x, s.cell.x));
    const int64_t x1 = std::min<int64_t>(top, last(t_hi.x, s.lo.x, s.cell.x));
    const int64_t y0 = std::max<int64_t>(0, first(t_lo.y, s.lo.y, s.cell.y));
    const int64_t y1 = std::min<int64_t>(top, last(t_hi.y, s.lo.y, s.cell.y));
    const double sign = area > 0.0 ? 1.0 : -1.0;
    const auto edge = [&](const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r) {
        return sign * ((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x));
    };
    for (int64_t y = y0; y <= y1; ++y) {
        for (int64_t x = x0; x <= x1; ++x) {
            const glm::dvec2 centre(s.lo.x + (static_cast<double>(x) + 0.5) * s.cell.x,
                                    s.lo.y + (static_cast<double>(y) + 0.5) * s.cell.y);
            if (edge(a, b, centre) >= 0.0 && edge(b, c, centre) >= 0.0 &&
                edge(c, a, centre) >= 0.0) {
                cells[static_cast<size_t>(y) * n + static_cast<size_t>(x)] = 1;
            }
        }
    }
}

std::vector<uint8_t> outline(const ObjectOutlines::Side& s, uint32_t n,
                             std::span<const glm::dvec3> positions,
                             std::span<const uint32_t> indices) {
    std::vector<uint8_t> cells(size_t{n} * n, 0);
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        if (indices[t] >= positions.size() || indices[t + 1] >= positions.size() ||
            indices[t + 2] >= positions.size())
            continue;
        draw(s, n, project(s, positions[indices[t]]), project(s, positions[indices[t + 1]]),
             project(s, positions[indices[t + 2]]), cells);
    }
    return cells;
}

}  // namespace

ObjectOutlines::ObjectOutlines(std::span<const glm::dvec3> positions,
                               std::span<const uint32_t> indices, uint32_t resolution)
    : n_(std::max(1u, resolution)) {
    for (size_t k = 0; k < sides_.size(); ++k) {
        Side& s = sides_[k];
        s.name = kSides[k].name;
        const glm::dvec3 d = glm::normalize(kSides[k].direction);
        // Any axis not along d makes the first side of the grid's plane.
        const glm::dvec3 helper = std::abs(d.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        s.u = glm::normalize(glm::cross(d, helper));
        s.v = glm::cross(d, s.u);
        glm::dvec2 lo(INFINITY), hi(-INFINITY);
        for (const uint32_t i : indices) {
            if (i >= positions.size()) continue;
            const glm::dvec2 p = project(s, positions[i]);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        if (!(hi.x > lo.x) || !(hi.y > lo.y)) continue;  // no outline from here: nothing to lose
        s.lo = lo;
        s.cell = (hi - lo) / static_cast<double>(n_);
        s.object = outline(s, n_, positions, indices);
        for (const uint8_t c : s.object) s.object_cells += c;
    }
}

OutlineShare ObjectOutlines::worst(std::span<const glm::dvec3> positions,
                                   std::span<const uint32_t> indices) const {
    OutlineShare out;
    for (const Side& s : sides_) {
        if (s.object_cells == 0) continue;
        const std::vector<uint8_t> cells = outline(s, n_, positions, indices);
        uint64_t covered = 0;
        for (size_t i = 0; i < cells.size(); ++i) covered += cells[i] & s.object[i];
        const double share = static_cast<double>(covered) / static_cast<double>(s.object_cells);
        if (share < out.share) out = {share, s.name};
    }
    return out;
}

}  // namespace occsim
