// The exact raster of one triangle, the reference that software depth buffers are checked
// against (the testing devices' TriangleRasterDevice, `occsim masked-replay`). Written to be
// obviously right rather than fast: double precision throughout, the triangle clipped to the near
// and far planes (z = -w and z = w, OpenGL's clip convention), one sample at each pixel centre,
// a sample exactly on an edge counted as covered (so the reference sees at least as much as any
// real rasteriser's image), both faces, depth as 1/w interpolated across the screen.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace occsim {

// Clips a polygon (clip coordinates) to the half-space dot(plane, v) >= 0.
inline std::vector<glm::dvec4> clipPolygon(const std::vector<glm::dvec4>& in,
                                           const glm::dvec4& plane) {
    std::vector<glm::dvec4> out;
    for (size_t i = 0; i < in.size(); ++i) {
        const glm::dvec4& p = in[i];
        const glm::dvec4& q = in[(i + 1) % in.size()];
        const double dp = glm::dot(plane, p), dq = glm::dot(plane, q);
        if (dp >= 0.0) out.push_back(p);
        if ((dp >= 0.0) != (dq >= 0.0)) out.push_back(p + (dp / (dp - dq)) * (q - p));
    }
    return out;
}

// Calls fragment(pixel, 1/w) for every pixel centre of a width × height viewport (pixel index
// row * width + column, row 0 at the bottom) that the triangle a, b, c (clip coordinates)
// covers.
template <class Fragment>
void rasteriseExactTriangle(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c,
                            uint32_t width, uint32_t height, Fragment&& fragment) {
    std::vector<glm::dvec4> polygon = {a, b, c};
    polygon = clipPolygon(polygon, glm::dvec4(0, 0, 1, 1));   // near: z >= -w
    polygon = clipPolygon(polygon, glm::dvec4(0, 0, -1, 1));  // far: z <= w
    for (size_t k = 1; k + 1 < polygon.size(); ++k) {
        const glm::dvec4 v[3] = {polygon[0], polygon[k], polygon[k + 1]};
        double x[3], y[3], iw[3];
        for (int i = 0; i < 3; ++i) {
            iw[i] = 1.0 / v[i].w;
            x[i] = (v[i].x * iw[i] + 1.0) * 0.5 * width;
            y[i] = (v[i].y * iw[i] + 1.0) * 0.5 * height;
        }
        const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if (!(std::abs(area) > 0.0)) continue;
        const int j0 = std::max(0, static_cast<int>(std::ceil(std::min({x[0], x[1], x[2]}) - 0.5)));
        const int j1 = std::min(static_cast<int>(width) - 1,
                                static_cast<int>(std::floor(std::max({x[0], x[1], x[2]}) - 0.5)));
        const int i0 = std::max(0, static_cast<int>(std::ceil(std::min({y[0], y[1], y[2]}) - 0.5)));
        const int i1 = std::min(static_cast<int>(height) - 1,
                                static_cast<int>(std::floor(std::max({y[0], y[1], y[2]}) - 0.5)));
        for (int i = i0; i <= i1; ++i) {
            for (int j = j0; j <= j1; ++j) {
                const double px = j + 0.5, py = i + 0.5;
                // Barycentric weights of the sample; all >= 0 inside (or on an edge).
                const double b0 = ((x[1] - px) * (y[2] - py) - (x[2] - px) * (y[1] - py)) / area;
                const double b1 = ((x[2] - px) * (y[0] - py) - (x[0] - px) * (y[2] - py)) / area;
                const double b2 = 1.0 - b0 - b1;
                if (b0 < 0.0 || b1 < 0.0 || b2 < 0.0) continue;
                fragment(static_cast<size_t>(i) * width + j, b0 * iw[0] + b1 * iw[1] + b2 * iw[2]);
            }
        }
    }
}

}  // namespace occsim
