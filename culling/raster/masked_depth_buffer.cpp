// Hasselgren, Andersson & Akenine-Möller, "Masked Software Occlusion Culling", HPG 2016: tiles
// with a coverage mask and two depth layers, merged conservatively. Written here from the paper;
// docs/masked.md lists what differs from it. The conventions and the rules are in the header.
#include "occsim/culling/raster/masked_depth_buffer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "culling/raster/masked_kernels.h"

namespace occsim {
namespace {

// Float inputs (the matrices, the eye, the transforms, the vertices) are rounded by at most half
// an ulp each; a few of them add up in one coordinate. This many ulps of the coordinates'
// magnitude bound the distance between where we put a point and where the exact inputs put it.
constexpr double kRoundingUlps = 8.0 * FLT_EPSILON;
// A rasteriser snaps vertices to this grid (viewport pixels; 8 sub-pixel bits, the fewest OpenGL
// implementations use).
constexpr double kSnapPx = 1.0 / 256.0;
// Triangles are clipped this far (relative) beyond the near plane: what a rasteriser keeps of a
// triangle crossing the near plane always contains what we keep.
constexpr double kNearClipMargin = 1e-4;

double maxAbs(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

}  // namespace

std::vector<uint32_t> edgeNeighbours(std::span<const uint32_t> indices) {
    struct Edge {
        uint64_t key;   // the two vertex indices, smaller first
        uint32_t slot;  // 3t + i
    };
    const size_t triangles = indices.size() / 3;
    std::vector<Edge> edges;
    edges.reserve(3 * triangles);
    for (size_t t = 0; t < triangles; ++t) {
        for (uint32_t i = 0; i < 3; ++i) {
            const uint64_t p = indices[3 * t + i], q = indices[3 * t + (i + 1) % 3];
            edges.push_back(
                {std::min(p, q) << 32 | std::max(p, q), static_cast<uint32_t>(3 * t + i)});
        }
    }
    std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
        return a.key < b.key || (a.key == b.key && a.slot < b.slot);
    });
    std::vector<uint32_t> out(3 * triangles, kNoNeighbour);
    for (size_t e = 0; e < edges.size();) {
        size_t end = e;
        while (end < edges.size() && edges[end].key == edges[e].key) ++end;
        if (end - e == 2) {
            const uint32_t s0 = edges[e].slot, s1 = edges[e + 1].slot;
            // The vertex opposite an edge is the triangle's third one: (i + 2) mod 3.
            out[s0] = indices[s1 - s1 % 3 + (s1 % 3 + 2) % 3];
            out[s1] = indices[s0 - s0 % 3 + (s0 % 3 + 2) % 3];
        }
        e = end;
    }
    return out;
}

namespace {

// Vertices compare by the bits of their coordinates: a total order even for NaN (which then
// welds only with its own bits), and -0 apart from +0 (not welding is always safe).
template <class Bits, int N, class Vertex>
std::vector<uint32_t> weldBy(std::span<const Vertex> positions, std::span<const uint32_t> indices) {
    auto key = [&](uint32_t v) {
        std::array<Bits, N> k;
        for (int c = 0; c < N; ++c) k[c] = std::bit_cast<Bits>(positions[v][c]);
        return k;
    };
    std::vector<uint32_t> order(positions.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const auto ka = key(a), kb = key(b);
        return ka < kb || (ka == kb && a < b);
    });
    // The first of each run of equal positions is its smallest index.
    std::vector<uint32_t> first(positions.size());
    for (size_t i = 0; i < order.size(); ++i) {
        const bool same = i > 0 && key(order[i - 1]) == key(order[i]);
        first[order[i]] = same ? first[order[i - 1]] : order[i];
    }
    std::vector<uint32_t> out(indices.begin(), indices.end());
    for (uint32_t& i : out) {
        if (i < first.size()) i = first[i];
    }
    return out;
}

}  // namespace

std::vector<uint32_t> weldedIndices(std::span<const glm::vec3> positions,
                                    std::span<const uint32_t> indices) {
    return weldBy<uint32_t, 3>(positions, indices);
}

std::vector<uint32_t> weldedIndices(std::span<const glm::dvec4> positions,
                                    std::span<const uint32_t> indices) {
    return weldBy<uint64_t, 4>(positions, indices);
}

bool maskedKernelAvailable(MaskedKernel kernel) {
    return kernel == MaskedKernel::Plain || masked_kernels::avx2Available();
}

std::string validMaskedLayout(const MaskedLayout& layout) {
    const uint32_t w = layout.cell_width, h = layout.cell_height;
    if (w != 8 && w != 16 && w != 32) {
        return "a depth cell's width must be 8, 16 or 32 pixels, not " + std::to_string(w);
    }
    if (h != 4 && h != 8) {
        return "a depth cell's height must be 4 or 8 pixels, not " + std::to_string(h);
    }
    return {};
}

MaskedDepthBuffer::MaskedDepthBuffer(MaskedKernel kernel, const MaskedLayout& layout)
    : kernel_(maskedKernelAvailable(kernel) ? kernel : MaskedKernel::Plain), layout_(layout) {
    if (const std::string problem = validMaskedLayout(layout); !problem.empty()) {
        throw std::invalid_argument(problem);
    }
    cells_across_ = kTileWidth / layout.cell_width;
    cells_down_ = kTileHeight / layout.cell_height;
    const uint32_t one_cell = layout.cell_width == 32 ? ~0u : (1u << layout.cell_width) - 1u;
    for (uint32_t c = 0; c < cells_across_; ++c)
        cell_columns_[c] = one_cell << (c * layout.cell_width);
}

bool MaskedDepthBuffer::layOut(uint32_t viewport_width, uint32_t viewport_height,
                               uint32_t max_width) {
    active_ = false;
    stats_ = MaskedBufferStats{};
    viewport_width_ = viewport_width;
    viewport_height_ = viewport_height;
    width_ = height_ = tiles_x_ = tiles_y_ = 0;
    tiles_.clear();
    if (viewport_width == 0 || viewport_height == 0) return false;

    if (max_width == 0) max_width = viewport_width;
    k_ = (viewport_width + max_width - 1) / max_width;
    width_ = (viewport_width + k_ - 1) / k_;
    height_ = (viewport_height + k_ - 1) / k_;
    tiles_x_ = (width_ + kTileWidth - 1) / kTileWidth;
    tiles_y_ = (height_ + kTileHeight - 1) / kTileHeight;
    tiles_.assign(static_cast<size_t>(tiles_x_) * tiles_y_, Tile{});
    const uint32_t columns_in_last = width_ - (tiles_x_ - 1) * kTileWidth;
    const uint32_t outside_columns = columns_in_last == kTileWidth ? 0u : ~0u << columns_in_last;
    std::fill(std::begin(right_outside_), std::end(right_outside_), outside_columns);
    top_outside_rows_ = tiles_y_ * kTileHeight - height_;
    return true;
}

void MaskedDepthBuffer::beginClipFrame(uint32_t viewport_width, uint32_t viewport_height,
                                       double near_w, uint32_t max_width) {
    ortho_scale_ = 0.0;
    if (!layOut(viewport_width, viewport_height, max_width)) return;
    view_projection_ = glm::dmat4(1.0);
    eye_ = glm::dvec3(0.0);
    near_ = near_w;
    frame_error_ = 0.0;
    focal_px_ = 0.5 * std::max(viewport_width, viewport_height);  // only scales a zero error
    active_ = std::isfinite(near_) && near_ > 0.0;
}

void MaskedDepthBuffer::rasteriseClipMesh(std::span<const glm::dvec4> clip,
                                          std::span<const uint32_t> indices,
                                          std::span<const uint32_t> neighbours) {
    const size_t triangles = indices.size() / 3;
    stats_.triangles += triangles;
    if (!active_ || triangles == 0) return;
    const bool have_neighbours = neighbours.size() == 3 * triangles;
    const bool closed = have_neighbours && std::find(neighbours.begin(), neighbours.end(),
                                                     kNoNeighbour) == neighbours.end();
    skip_facing_ = closed ? 1 : 0;
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t i0 = indices[3 * t], i1 = indices[3 * t + 1], i2 = indices[3 * t + 2];
        if (i0 >= clip.size() || i1 >= clip.size() || i2 >= clip.size()) continue;
        const glm::dvec4* opposite[3] = {nullptr, nullptr, nullptr};
        for (uint32_t i = 0; i < 3 && have_neighbours; ++i) {
            const uint32_t n = neighbours[3 * t + i];
            if (n < clip.size()) opposite[i] = &clip[n];
        }
        rasteriseClipTriangle(clip[i0], clip[i1], clip[i2], 0.0, opposite);
    }
    skip_facing_ = 0;
}

void MaskedDepthBuffer::beginOrthographicFrame(const glm::mat4& view_projection,
                                               uint32_t viewport_width, uint32_t viewport_height,
                                               uint32_t max_width) {
    ortho_scale_ = 0.0;
    if (!layOut(viewport_width, viewport_height, max_width)) return;
    view_projection_ = glm::dmat4(view_projection);
    const glm::dmat4& m = view_projection_;
    const glm::dvec3 row_x(m[0][0], m[1][0], m[2][0]), row_y(m[0][1], m[1][1], m[2][1]);
    const glm::dvec3 row_z(m[0][2], m[1][2], m[2][2]), row_w(m[0][3], m[1][3], m[2][3]);
    const double w = m[3][3];
    if (row_w != glm::dvec3(0.0) || !(w > 0.0) || !std::isfinite(w)) return;
    // z after the divide moves this much per metre.
    const double z_per_metre = glm::length(row_z) / w;
    if (!(z_per_metre > 0.0) || !std::isfinite(z_per_metre)) return;
    ortho_scale_ = std::min(1.0, 1.0 / z_per_metre);
    eye_ = glm::dvec3(0.0);
    // The near plane (z = -1) at w' = s / 3; the nearest w' is never below s / 3 inside the view.
    near_ = ortho_scale_ / 3.0;
    // A metre across is this many viewport pixels; w' <= s inside the view, so focal / w' bounds
    // the pixels a metre's rounding moves a point by.
    focal_px_ = std::max(0.5 * viewport_width * glm::length(row_x),
                         0.5 * viewport_height * glm::length(row_y)) /
                w * ortho_scale_;
    // The rounding of the matrix, as the eye's in a perspective frame: of the coordinates of the
    // view's centre (the point the matrix takes to the clip origin).
    const glm::dmat3 linear(m);
    if (!(std::abs(glm::determinant(linear)) > 0.0)) return;
    const glm::dvec3 centre = -(glm::inverse(linear) * glm::dvec3(m[3]));
    frame_error_ = kRoundingUlps * (maxAbs(centre) + 1.0);
    active_ = std::isfinite(focal_px_) && focal_px_ > 0.0 && std::isfinite(frame_error_);
    clip_scratch_.reserve(64);
}

glm::dvec4 MaskedDepthBuffer::bufferClip(const glm::dvec4& clip) const {
    if (ortho_scale_ == 0.0) return clip;
    const double z = clip.z / clip.w;
    if (!(z < 1.0)) return glm::dvec4(NAN);
    const double w = ortho_scale_ / (2.0 - z);
    return glm::dvec4(clip.x / clip.w * w, clip.y / clip.w * w, z * w, w);
}

void MaskedDepthBuffer::beginFrame(const glm::mat4& view_projection, glm::vec3 eye,
                                   uint32_t viewport_width, uint32_t viewport_height,
                                   uint32_t max_width) {
    ortho_scale_ = 0.0;
    if (!layOut(viewport_width, viewport_height, max_width)) return;
    view_projection_ = glm::dmat4(view_projection);
    eye_ = glm::dvec3(eye);
    // The near plane from the matrix: with z = a·w + t at the eye (a = (f+n)/(f-n) and
    // t = -2fn/(f-n) for glm::perspective), the plane z = -w lies at w = -t / (a + 1).
    const glm::dmat4& m = view_projection_;
    const glm::dvec3 row_x(m[0][0], m[1][0], m[2][0]), row_y(m[0][1], m[1][1], m[2][1]);
    const glm::dvec3 row_z(m[0][2], m[1][2], m[2][2]), row_w(m[0][3], m[1][3], m[2][3]);
    const double w_scale = glm::length(row_w);
    if (!(w_scale > 0.0) || !std::isfinite(w_scale)) return;
    const double a = glm::dot(row_z, row_w) / (w_scale * w_scale);
    const double z_at_eye = glm::dot(row_z, eye_) + m[3][2];
    near_ = -z_at_eye / (a + 1.0);
    focal_px_ = std::max(0.5 * viewport_width * glm::length(row_x),
                         0.5 * viewport_height * glm::length(row_y)) /
                w_scale;
    frame_error_ = kRoundingUlps * (maxAbs(eye_) + 1.0);
    active_ = std::isfinite(near_) && near_ > 0.0 && std::isfinite(focal_px_) && focal_px_ > 0.0;
    clip_scratch_.reserve(64);
}

void MaskedDepthBuffer::rasteriseMesh(std::span<const glm::vec3> positions,
                                      std::span<const uint32_t> indices,
                                      const glm::mat4& object_to_culling,
                                      std::span<const uint32_t> neighbours) {
    const size_t triangles = indices.size() / 3;
    stats_.triangles += triangles;
    if (!active_ || triangles == 0) return;
    // In double: a matrix composed of float inputs rounds nothing more.
    const glm::dmat4 model(object_to_culling);
    const glm::dmat4 to_clip = view_projection_ * model;
    double radius = 0.0;
    clip_scratch_.resize(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        const glm::dvec3 p(positions[i]);
        radius = std::max(radius, maxAbs(p));
        clip_scratch_[i] = bufferClip(to_clip * glm::dvec4(p, 1.0));
    }
    double scale = 0.0;
    for (int c = 0; c < 3; ++c) scale = std::max(scale, maxAbs(glm::dvec3(model[c])));
    const double error =
        frame_error_ + kRoundingUlps * (maxAbs(glm::dvec3(model[3])) + scale * radius);
    if (!std::isfinite(error)) return;
    const bool have_neighbours = neighbours.size() == 3 * triangles;
    // A closed mesh's back faces lie behind its front faces: skip them (a mirroring transform
    // turns which winding faces the eye).
    const bool closed = have_neighbours && std::find(neighbours.begin(), neighbours.end(),
                                                     kNoNeighbour) == neighbours.end();
    skip_facing_ = closed ? (glm::determinant(glm::dmat3(model)) < 0.0 ? -1 : 1) : 0;
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t i0 = indices[3 * t], i1 = indices[3 * t + 1], i2 = indices[3 * t + 2];
        if (i0 >= positions.size() || i1 >= positions.size() || i2 >= positions.size()) continue;
        const glm::dvec4* opposite[3] = {nullptr, nullptr, nullptr};
        for (uint32_t i = 0; i < 3 && have_neighbours; ++i) {
            const uint32_t n = neighbours[3 * t + i];
            if (n < positions.size()) opposite[i] = &clip_scratch_[n];
        }
        rasteriseClipTriangle(clip_scratch_[i0], clip_scratch_[i1], clip_scratch_[i2], error,
                              opposite);
    }
    skip_facing_ = 0;
}

void MaskedDepthBuffer::rasteriseTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    ++stats_.triangles;
    if (!active_) return;
    const glm::dvec3 p[3] = {glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)};
    const double error =
        frame_error_ + kRoundingUlps * std::max({maxAbs(p[0]), maxAbs(p[1]), maxAbs(p[2])});
    rasteriseClipTriangle(bufferClip(view_projection_ * glm::dvec4(p[0], 1.0)),
                          bufferClip(view_projection_ * glm::dvec4(p[1], 1.0)),
                          bufferClip(view_projection_ * glm::dvec4(p[2], 1.0)), error);
}

void MaskedDepthBuffer::rasteriseClipTriangle(const glm::dvec4& a, const glm::dvec4& b,
                                              const glm::dvec4& c, double position_error,
                                              const glm::dvec4* const* opposite) {
    // Clip against w >= clip_w (Sutherland-Hodgman on one plane): at most four vertices.
    const double clip_w = near_ * (1.0 + kNearClipMargin) + 2.0 * position_error;
    const glm::dvec4 in[3] = {a, b, c};
    glm::dvec4 out[4];
    int n = 0;
    bool clipped = false;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec4& p = in[i];
        const glm::dvec4& q = in[(i + 1) % 3];
        if (!std::isfinite(p.x + p.y + p.z + p.w)) return;
        const double dp = p.w - clip_w, dq = q.w - clip_w;
        if (dp >= 0.0) out[n++] = p;
        clipped |= dp < 0.0;
        if ((dp >= 0.0) != (dq >= 0.0)) {
            // From the vertex in front, whichever way the edge is walked: the triangle across a
            // shared edge gets the same point.
            const glm::dvec4& f = dp >= 0.0 ? p : q;
            const glm::dvec4& behind = dp >= 0.0 ? q : p;
            const double df = dp >= 0.0 ? dp : dq, db = dp >= 0.0 ? dq : dp;
            glm::dvec4 x = f + (df / (df - db)) * (behind - f);
            x.w = std::max(x.w, clip_w);  // on the plane, never in front of it by rounding
            out[n++] = x;
        }
    }
    if (n < 3) return;
    if (!clipped && opposite != nullptr) {
        // Unclipped: an edge may go without margin when the triangle across it is unclipped too.
        const glm::dvec4* across[3] = {nullptr, nullptr, nullptr};
        for (int i = 0; i < 3; ++i) {
            if (opposite[i] != nullptr && opposite[i]->w >= clip_w) across[i] = opposite[i];
        }
        rasteriseScreenTriangle(out, position_error, across);
        return;
    }
    // Clipped to a triangle or a convex quad: the quad's two halves share their diagonal.
    const glm::dvec4 first[3] = {out[0], out[1], out[2]};
    const glm::dvec4* first_across[3] = {nullptr, nullptr, n == 4 ? &out[3] : nullptr};
    rasteriseScreenTriangle(first, position_error, first_across);
    if (n == 4) {
        const glm::dvec4 second[3] = {out[0], out[2], out[3]};
        const glm::dvec4* second_across[3] = {&out[1], nullptr, nullptr};
        rasteriseScreenTriangle(second, position_error, second_across);
    }
}

void MaskedDepthBuffer::rasteriseScreenTriangle(const glm::dvec4* v, double position_error,
                                                const glm::dvec4* const* opposite) {
    // Buffer coordinates: buffer pixel (X, Y) has its centre at (X, Y); it stands for the k×k
    // viewport pixels whose centres lie within h of it (h = (k - 1) / 2k buffer pixels).
    const double su = 0.5 * viewport_width_ / k_, sv = 0.5 * viewport_height_ / k_;
    double u[3], w_min = INFINITY, inv_w_min = INFINITY;
    double vv[3], inv_w[3];
    for (int i = 0; i < 3; ++i) {
        inv_w[i] = 1.0 / v[i].w;
        u[i] = (v[i].x * inv_w[i] + 1.0) * su - 0.5;
        vv[i] = (v[i].y * inv_w[i] + 1.0) * sv - 0.5;
        w_min = std::min(w_min, v[i].w);
        inv_w_min = std::min(inv_w_min, inv_w[i]);
    }
    const double area2 = (u[1] - u[0]) * (vv[2] - vv[0]) - (u[2] - u[0]) * (vv[1] - vv[0]);
    if (!std::isfinite(area2) || area2 == 0.0) return;
    if (skip_facing_ * area2 < 0.0) return;  // a back face of a closed mesh

    // The sample points that may be covered: the bounding box, clipped to the buffer.
    const double u_lo = std::min({u[0], u[1], u[2]}), u_hi = std::max({u[0], u[1], u[2]});
    const double v_lo = std::min({vv[0], vv[1], vv[2]}), v_hi = std::max({vv[0], vv[1], vv[2]});
    const int32_t x_lo = static_cast<int32_t>(std::max(0.0, std::ceil(u_lo)));
    const int32_t x_hi = static_cast<int32_t>(std::min(width_ - 1.0, std::floor(u_hi)));
    const int32_t y_lo = static_cast<int32_t>(std::max(0.0, std::ceil(v_lo)));
    const int32_t y_hi = static_cast<int32_t>(std::min(height_ - 1.0, std::floor(v_hi)));
    if (x_lo > x_hi || y_lo > y_hi) return;

    // How far inside every edge a sample point must be, in buffer pixels: the k×k block's half
    // extent, the rasteriser's snapping, and where rounding may have put the vertices.
    const double margin = (k_ - 1.0) / (2.0 * k_) +
                          (kCoverageMarginPx + 2.0 * position_error * focal_px_ / w_min) / k_;
    masked_kernels::Edges edges;
    double longest = 0.0;
    for (int i = 0; i < 3; ++i) {
        // The edge from its lexicographically smaller end, so that the triangle across a shared
        // edge computes the same line, negated exactly: no sample falls between the two.
        int p = i, q = (i + 1) % 3;
        if (u[q] < u[p] || (u[q] == u[p] && vv[q] < vv[p])) std::swap(p, q);
        const double du = u[q] - u[p], dv = vv[q] - vv[p];
        longest = std::max(longest, std::hypot(du, dv));
        // e(X, Y) = a·X + b·Y + c, positive inside (towards the third vertex).
        const int third = 3 - i - (i + 1) % 3;
        const double towards = dv * u[p] - du * vv[p] - dv * u[third] + du * vv[third];
        const double s = towards > 0.0 ? 1.0 : -1.0;
        edges.a[i] = -s * dv;
        edges.b[i] = s * du;
        edges.c[i] = s * (dv * u[p] - du * vv[p]);
        // A shared edge with the other triangle on its far side (on screen) needs no margin at
        // full resolution: whatever sample one of the two leaves, the other covers.
        bool shared = false;
        if (opposite[i] != nullptr) {
            const glm::dvec4& o = *opposite[i];
            const double uo = (o.x / o.w + 1.0) * su - 0.5, vo = (o.y / o.w + 1.0) * sv - 0.5;
            shared = edges.a[i] * uo + edges.b[i] * vo + edges.c[i] < 0.0;
        }
        const double edge_margin = shared ? (k_ - 1.0) / (2.0 * k_) : margin;
        edges.margin[i] = (std::abs(edges.a[i]) + std::abs(edges.b[i])) * edge_margin;
        edges.inclusive[i] =
            shared && (edges.a[i] > 0.0 || (edges.a[i] == 0.0 && edges.b[i] > 0.0));
    }
    edges.x_lo = x_lo;
    edges.x_hi = x_hi;

    // Depth: 1/w is affine in screen space. Per cell, the plane's farthest value over the covered
    // pixel centres, reached out by `depth_reach`, never farther than the triangle's farthest
    // vertex. The reach is the coverage margin (the block's half extent, snapping, rounding)
    // plus how far a rasteriser's plane through vertices snapped by 1/256 pixel may tilt: by the
    // snapping times the triangle's length over its height. A sliver (less than a viewport pixel
    // high) gets its farthest vertex.
    const double dz1 = inv_w[1] - inv_w[0], dz2 = inv_w[2] - inv_w[0];
    const double plane_a = (dz1 * (vv[2] - vv[0]) - dz2 * (vv[1] - vv[0])) / area2;
    const double plane_b = ((u[1] - u[0]) * dz2 - (u[2] - u[0]) * dz1) / area2;
    const double plane_c = inv_w[0] - plane_a * u[0] - plane_b * vv[0];
    const double height = std::abs(area2) / longest;  // buffer pixels
    const bool sliver = height * k_ < 1.0;
    const double depth_reach = margin + 2.0 * (kSnapPx / k_) * (longest / height);
    const double depth_scale =
        (1.0 - kDepthMargin) * (1.0 - 2.0 * position_error / std::max(w_min, 1e-300));
    if (!(depth_scale > 0.0)) return;
    ++stats_.triangles_rasterised;

    int32_t xl[kTileHeight], xr[kTileHeight];
    uint32_t coverage[kTileHeight];
    for (uint32_t ty = static_cast<uint32_t>(y_lo) / kTileHeight;
         ty <= static_cast<uint32_t>(y_hi) / kTileHeight; ++ty) {
        const int32_t row0 = static_cast<int32_t>(ty * kTileHeight);
        if (kernel_ == MaskedKernel::Avx2) {
            masked_kernels::spansAvx2(edges, row0, y_lo, y_hi, xl, xr);
        } else {
            masked_kernels::spansPlain(edges, row0, y_lo, y_hi, xl, xr);
        }
        int32_t span_lo = INT32_MAX, span_hi = INT32_MIN;
        for (uint32_t r = 0; r < kTileHeight; ++r) {
            if (xl[r] > xr[r]) continue;
            span_lo = std::min(span_lo, xl[r]);
            span_hi = std::max(span_hi, xr[r]);
        }
        if (span_lo > span_hi) continue;
        for (uint32_t tx = static_cast<uint32_t>(span_lo) / kTileWidth;
             tx <= static_cast<uint32_t>(span_hi) / kTileWidth; ++tx) {
            const int32_t col0 = static_cast<int32_t>(tx * kTileWidth);
            if (kernel_ == MaskedKernel::Avx2) {
                masked_kernels::coverageAvx2(xl, xr, col0, coverage);
            } else {
                masked_kernels::coveragePlain(xl, xr, col0, coverage);
            }
            uint32_t any = 0;
            for (uint32_t r = 0; r < kTileHeight; ++r) any |= coverage[r];
            if (any == 0) continue;
            const uint32_t tile = ty * tiles_x_ + tx;
            for (uint32_t cy = 0; cy < cells_down_; ++cy) {
                const uint32_t r0 = cy * layout_.cell_height, r1 = r0 + layout_.cell_height;
                for (uint32_t cx = 0; cx < cells_across_; ++cx) {
                    uint32_t cell_coverage[kTileHeight] = {};
                    uint32_t columns = 0;
                    int32_t row_lo = -1, row_hi = -1;
                    for (uint32_t r = r0; r < r1; ++r) {
                        cell_coverage[r] = coverage[r] & cell_columns_[cx];
                        if (cell_coverage[r] == 0) continue;
                        columns |= cell_coverage[r];
                        if (row_lo < 0) row_lo = static_cast<int32_t>(r);
                        row_hi = static_cast<int32_t>(r);
                    }
                    if (columns == 0) continue;
                    double far = inv_w_min;
                    if (!sliver) {
                        // The plane's farthest value over the covered pixels of the cell.
                        const double x0 = col0 + std::countr_zero(columns);
                        const double x1 = col0 + (31 - std::countl_zero(columns));
                        const double y0 = row0 + row_lo, y1 = row0 + row_hi;
                        const double plane_far =
                            plane_c + plane_a * (plane_a > 0.0 ? x0 : x1) +
                            plane_b * (plane_b > 0.0 ? y0 : y1) -
                            (std::abs(plane_a) + std::abs(plane_b)) * depth_reach;
                        far = std::max(far, plane_far);
                    }
                    updateCell(tile, cy * cells_across_ + cx, cell_coverage,
                               static_cast<float>(far * depth_scale));
                }
            }
        }
    }
}

bool MaskedDepthBuffer::cellFull(uint32_t tile, uint32_t cell,
                                 const uint32_t (&mask)[kTileHeight]) const {
    const bool last_column = tile % tiles_x_ == tiles_x_ - 1;
    const bool last_row = tile / tiles_x_ == tiles_y_ - 1;
    const uint32_t columns = cell_columns_[cell % cells_across_];
    const uint32_t r0 = (cell / cells_across_) * layout_.cell_height;
    for (uint32_t r = r0; r < r0 + layout_.cell_height; ++r) {
        if (last_row && r >= kTileHeight - top_outside_rows_) continue;  // past the top edge
        const uint32_t outside = last_column ? right_outside_[r] : 0u;
        if (((mask[r] | outside) & columns) != columns) return false;
    }
    return true;
}

void MaskedDepthBuffer::updateCell(uint32_t tile, uint32_t cell,
                                   const uint32_t (&coverage)[kTileHeight], float depth) {
    Tile& t = tiles_[tile];
    float& z0 = t.z0[cell];
    float& z1 = t.z1[cell];
    // Rounding to float must not make the triangle nearer than computed.
    if (!(depth > z0)) return;  // nothing the cell does not know already (or NaN)
    ++stats_.tile_updates;
    const uint32_t columns = cell_columns_[cell % cells_across_];
    const uint32_t r0 = (cell / cells_across_) * layout_.cell_height;
    const uint32_t r1 = r0 + layout_.cell_height;
    uint32_t held = 0;  // pixels of the cell in the working layer
    uint32_t merged[kTileHeight] = {};
    for (uint32_t r = r0; r < r1; ++r) {
        held += static_cast<uint32_t>(std::popcount(t.mask[r] & columns));
        merged[r] = (t.mask[r] & columns) | coverage[r];
    }
    const bool covers_cell = cellFull(tile, cell, coverage);
    bool discard = false;
    if (layout_.merge == MaskedMerge::Quick) {
        // The paper's rule: a triangle covering the cell, or one the working layer lies nearer
        // to z0 than to, replaces the working layer.
        discard = covers_cell || held == 0 || 2.0f * z1 - (depth + z0) < 0.0f;
    } else {
        // Of the three outcomes, the one that leaves the cell the nearest bounds where boxes
        // are tested: first the reference depth (a full mask promoted), then, where boxes are
        // tested against the working layer too, the sum of every pixel's bound. Ties go to
        // merging, then to replacing. Dropping an occluder is always safe.
        const double n = layout_.cell_width * layout_.cell_height;
        struct Outcome {
            double z0, sum;
        };
        auto outcome = [&](double in_mask, double mask_depth, bool full) {
            if (full) return Outcome{mask_depth, n * mask_depth};
            return Outcome{z0, in_mask * mask_depth + (n - in_mask) * z0};
        };
        const bool by_sum = layout_.test_working_layer;
        auto better = [by_sum](const Outcome& a, const Outcome& b) {
            if (a.z0 != b.z0) return a.z0 > b.z0;
            return by_sum && a.sum > b.sum;
        };
        uint32_t merged_count = 0, coverage_count = 0;
        for (uint32_t r = r0; r < r1; ++r) {
            merged_count += static_cast<uint32_t>(std::popcount(merged[r]));
            coverage_count += static_cast<uint32_t>(std::popcount(coverage[r]));
        }
        const Outcome keep = outcome(held, held ? z1 : z0, false);
        const Outcome merge =
            outcome(merged_count, held ? std::min(z1, depth) : depth, cellFull(tile, cell, merged));
        const Outcome replace = outcome(coverage_count, depth, covers_cell);
        if (better(keep, merge) && better(keep, replace)) return;
        discard = held == 0 || better(replace, merge);
    }
    if (discard) {
        // The pixels the working layer leaves fall back to z0, which bounds them already.
        for (uint32_t r = r0; r < r1; ++r) t.mask[r] = (t.mask[r] & ~columns) | coverage[r];
        z1 = depth;
    } else {
        for (uint32_t r = r0; r < r1; ++r) t.mask[r] |= coverage[r];
        z1 = std::min(z1, depth);
    }
    if (cellFull(tile, cell, t.mask)) {
        z0 = z1;  // every pixel of the cell is bounded by z1 > z0 now
        for (uint32_t r = r0; r < r1; ++r) t.mask[r] &= ~columns;
        z1 = 0.0f;
    }
}

float MaskedDepthBuffer::pixelBound(uint32_t x, uint32_t y) const {
    if (x >= width_ || y >= height_) return 0.0f;
    const Tile& t = tiles_[(y / kTileHeight) * tiles_x_ + x / kTileWidth];
    const uint32_t cell = cellIndex(x % kTileWidth, y % kTileHeight);
    const bool in_mask = (t.mask[y % kTileHeight] >> (x % kTileWidth)) & 1u;
    return in_mask && layout_.test_working_layer ? t.z1[cell] : t.z0[cell];
}

namespace {

struct ProjectedBox {
    bool valid = false;  // false: reaches to the eye (or not finite): visible
    double x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0;  // viewport pixels
    double w_min = 0;
    double error = 0;  // metres
};

}  // namespace

// `ortho_scale`: an orthographic frame's s (MaskedDepthBuffer::beginOrthographicFrame), 0 for a
// perspective one.
static ProjectedBox projectBox(const glm::dmat4& view_projection, const Aabb& box,
                               double frame_error, double near, uint32_t width, uint32_t height,
                               double ortho_scale) {
    ProjectedBox p;
    if (!isFiniteAndOrdered(box)) return p;
    const glm::dvec3 lo(box.min), hi(box.max);
    p.error = frame_error + kRoundingUlps * std::max(maxAbs(lo), maxAbs(hi));
    p.w_min = INFINITY;
    p.x_lo = p.y_lo = INFINITY;
    p.x_hi = p.y_hi = -INFINITY;
    glm::dvec4 clip[8];
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 corner(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        clip[i] = view_projection * glm::dvec4(corner, 1.0);
        if (ortho_scale > 0.0) {
            // At the stand-in w' (bufferClip), a corner past the far plane taken nearer.
            const double z = std::min(clip[i].z / clip[i].w, 1.5);
            const double w = ortho_scale / (2.0 - z);
            clip[i] = glm::dvec4(clip[i].x / clip[i].w * w, clip[i].y / clip[i].w * w, z * w, w);
        }
        p.w_min = std::min(p.w_min, clip[i].w);
    }
    // w is linear, so its minimum over the box is at a corner. A box this close to the eye
    // (half the near distance, or nearer) is visible without further ado.
    if (!(p.w_min - p.error > 0.5 * near)) return p;
    for (const glm::dvec4& c : clip) {
        const double x = (c.x / c.w + 1.0) * 0.5 * width;
        const double y = (c.y / c.w + 1.0) * 0.5 * height;
        p.x_lo = std::min(p.x_lo, x);
        p.x_hi = std::max(p.x_hi, x);
        p.y_lo = std::min(p.y_lo, y);
        p.y_hi = std::max(p.y_hi, y);
    }
    p.valid = std::isfinite(p.x_lo + p.x_hi + p.y_lo + p.y_hi);
    return p;
}

bool MaskedDepthBuffer::testBox(const Aabb& box) {
    ++stats_.boxes_tested;
    if (!active_) return true;
    const ProjectedBox p = projectBox(view_projection_, box, frame_error_, near_, viewport_width_,
                                      viewport_height_, ortho_scale_);
    if (!p.valid) return true;
    return testProjected(p.x_lo, p.x_hi, p.y_lo, p.y_hi, p.w_min, p.error);
}

bool MaskedDepthBuffer::testRect(double x_lo, double x_hi, double y_lo, double y_hi, double w_min) {
    ++stats_.boxes_tested;
    if (!active_) return true;
    if (!(w_min > 0.5 * near_) || !std::isfinite(x_lo + x_hi + y_lo + y_hi)) return true;
    return testProjected(x_lo, x_hi, y_lo, y_hi, w_min, 0.0);
}

bool MaskedDepthBuffer::testProjected(double x_lo, double x_hi, double y_lo, double y_hi,
                                      double w_min, double error) {
    // The viewport pixels whose centres the box's contents may cover, rounded outward.
    const double margin = kBoxMarginPx + 2.0 * error * focal_px_ / (w_min - error);
    const double j0 = std::max(0.0, std::ceil(x_lo - margin - 0.5));
    const double j1 = std::min(viewport_width_ - 1.0, std::floor(x_hi + margin - 0.5));
    const double i0 = std::max(0.0, std::ceil(y_lo - margin - 0.5));
    const double i1 = std::min(viewport_height_ - 1.0, std::floor(y_hi + margin - 0.5));
    if (j0 > j1 || i0 > i1) {
        ++stats_.boxes_hidden;  // between pixel centres or off screen: no pixel to show in
        return false;
    }
    const double nearest = (1.0 + kDepthMargin) / (w_min - error);
    const uint32_t x0 = static_cast<uint32_t>(j0) / k_, x1 = static_cast<uint32_t>(j1) / k_;
    const uint32_t y0 = static_cast<uint32_t>(i0) / k_, y1 = static_cast<uint32_t>(i1) / k_;
    // Cell by cell over the rectangle, in buffer pixels.
    const uint32_t cw = layout_.cell_width, ch = layout_.cell_height;
    for (uint32_t cy = y0 / ch; cy <= y1 / ch; ++cy) {
        for (uint32_t cx = x0 / cw; cx <= x1 / cw; ++cx) {
            const uint32_t tx = cx * cw / kTileWidth, ty = cy * ch / kTileHeight;
            const Tile& t = tiles_[ty * tiles_x_ + tx];
            const uint32_t cell = cellIndex(cx * cw % kTileWidth, cy * ch % kTileHeight);
            if (nearest < t.z0[cell]) continue;  // behind every pixel of the cell
            if (layout_.test_working_layer && nearest < t.z1[cell]) {
                // Hidden where the mask is set: visible if the rectangle has a pixel outside it.
                const uint32_t c0 = std::max(x0, cx * cw) - tx * kTileWidth;
                const uint32_t c1 = std::min(x1, cx * cw + cw - 1) - tx * kTileWidth;
                const uint32_t columns = (~0u >> (kTileWidth - 1 - c1)) & (~0u << c0);
                const uint32_t r0 = std::max(y0, cy * ch) - ty * kTileHeight;
                const uint32_t r1 = std::min(y1, cy * ch + ch - 1) - ty * kTileHeight;
                bool covered = true;
                for (uint32_t r = r0; r <= r1 && covered; ++r) {
                    covered = (columns & ~t.mask[r]) == 0;
                }
                if (covered) continue;
            }
            return true;
        }
    }
    ++stats_.boxes_hidden;
    return false;
}

double MaskedDepthBuffer::screenExtent(const Aabb& box) const {
    if (!active_) return INFINITY;
    if (isEmpty(box)) return 0.0;
    const ProjectedBox p = projectBox(view_projection_, box, frame_error_, near_, viewport_width_,
                                      viewport_height_, ortho_scale_);
    if (!p.valid) return INFINITY;
    return std::max(p.x_hi - p.x_lo, p.y_hi - p.y_lo) / viewport_height_;
}

}  // namespace occsim
