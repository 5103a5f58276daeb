// The rules that keep a hierarchical depth buffer (a depth pyramid) conservative, as pure
// functions, so that the GPU pyramid (render/gl_depth_pyramid.cpp, whose shaders use the same
// integer formulas) and the software one (occsim/culling/testing/software_depth_pyramid.h) cannot
// drift apart, and each rule has a unit test that fails when it is broken
// (tests/culling/testing/test_software_depth_pyramid.cpp).
//
// 1. The base. Level 0 is the largest power of two no larger than the viewport on each axis, so
//    that every later level halves it exactly and each of their texels reduces at most 2x2 texels
//    of the level below. A base texel t covers the pixels its area [t*V/B, (t+1)*V/B) overlaps,
//    all of them (up to 3 per axis, as V/B < 2): firstCovered()..lastCovered(). The same formula
//    with V = 2B (or V = B = 1, an axis already down to one texel) is the 2x2 (or 1) reduction of
//    the later levels.
// 2. Farthest. Each texel holds the farthest depth of what it covers (the minimum with reverse-Z,
//    the maximum with conventional depth or distances): a bound nearer than it may show.
// 3. The level. From the bound's footprint in base texels, rounded UP: the coarsest level needed
//    for the footprint to span at most 2 texels per axis is ceil(log2(extent)). Rounding down
//    (floor) leaves footprints of 3 texels, which a reader of 2x2 texels gets wrong.
// 4. The footprint. Every texel the bound touches at that level is read, never a fixed 2x2 from a
//    rounded corner.
// 5. The near plane. A bound that reaches the near plane (or the eye plane: its projection is
//    not a rectangle on screen) is visible without a test.
//
// Rectangles are inclusive ranges of whole pixels or texels; pixel (0, 0) is the bottom left, as
// in OpenGL's window coordinates.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace occsim::hzb {

// An inclusive range of pixels or texels: [x0, x1] x [y0, y1].
struct TexelRect {
    uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool operator==(const TexelRect&) const = default;
};

// Rule 1: the largest power of two no larger than `viewport` (1 for 0 and 1).
constexpr uint32_t pyramidBaseSize(uint32_t viewport) {
    return viewport <= 1 ? 1u : std::bit_floor(viewport);
}

// The size of `level` on an axis whose base is `base` texels: halved per level, at least 1.
constexpr uint32_t levelSize(uint32_t base, uint32_t level) {
    return level >= 32 ? 1u : std::max(1u, base >> level);
}

// Levels down to 1x1: 1 + log2 of the larger base side.
constexpr uint32_t pyramidLevelCount(uint32_t base_width, uint32_t base_height) {
    return static_cast<uint32_t>(std::bit_width(std::max({base_width, base_height, 1u})));
}

// Rule 1: the first and last of `fine` cells (pixels, or texels of the level below) that cell t
// of `coarse` cells (coarse <= fine) covers: those its area [t*fine/coarse, (t+1)*fine/coarse)
// overlaps.
constexpr uint32_t firstCovered(uint32_t t, uint32_t fine, uint32_t coarse) {
    return static_cast<uint32_t>(uint64_t{t} * fine / coarse);
}
constexpr uint32_t lastCovered(uint32_t t, uint32_t fine, uint32_t coarse) {
    return static_cast<uint32_t>(((uint64_t{t} + 1) * fine + coarse - 1) / coarse - 1);
}

// The inverse: the first and last coarse cells whose coverage includes fine cell p. A bound's
// pixels map to every base texel that covers any of them.
constexpr uint32_t firstCovering(uint32_t p, uint32_t fine, uint32_t coarse) {
    return static_cast<uint32_t>(uint64_t{p} * coarse / fine);
}
constexpr uint32_t lastCovering(uint32_t p, uint32_t fine, uint32_t coarse) {
    return static_cast<uint32_t>(((uint64_t{p} + 1) * coarse + fine - 1) / fine - 1);
}

// The base texels that cover the pixels `pixels` of a viewport_w x viewport_h viewport.
constexpr TexelRect baseTexelsOf(const TexelRect& pixels, uint32_t viewport_w, uint32_t viewport_h,
                                 uint32_t base_w, uint32_t base_h) {
    return {
        firstCovering(pixels.x0, viewport_w, base_w), firstCovering(pixels.y0, viewport_h, base_h),
        lastCovering(pixels.x1, viewport_w, base_w), lastCovering(pixels.y1, viewport_h, base_h)};
}

// Rule 3: the level at which a footprint of `base_texels` spans at most 2 texels per axis:
// ceil(log2(the larger extent)), rounded up.
constexpr uint32_t pyramidLevelFor(const TexelRect& base_texels) {
    const uint32_t extent =
        std::max(base_texels.x1 - base_texels.x0, base_texels.y1 - base_texels.y0) + 1;
    return extent <= 1 ? 0u : static_cast<uint32_t>(std::bit_width(extent - 1));
}

// Rule 4: every texel of `level` that the footprint `base_texels` touches.
constexpr TexelRect footprintAt(const TexelRect& base_texels, uint32_t level) {
    return {base_texels.x0 >> level, base_texels.y0 >> level, base_texels.x1 >> level,
            base_texels.y1 >> level};
}

// The pixels whose squares a window-coordinate rectangle (x from 0 to width, y from 0 to height,
// continuous) touches, clamped to the viewport; at least one pixel. A pixel is drawn when its
// centre is inside a triangle, so this holds every pixel a triangle inside the rectangle can
// cover, with half a pixel to spare for the rasteriser's rounding.
inline TexelRect pixelsTouched(double x0, double y0, double x1, double y1, uint32_t width,
                               uint32_t height) {
    const auto clampTo = [](double v, uint32_t n) {
        const double c = std::floor(v);
        // NaN lands on 0 (std::clamp keeps NaN; the comparison form does not).
        return static_cast<uint32_t>(c > 0.0 ? std::min(c, double(n - 1)) : 0.0);
    };
    TexelRect r{clampTo(x0, width), clampTo(y0, height), clampTo(x1, width), clampTo(y1, height)};
    r.x1 = std::max(r.x1, r.x0);
    r.y1 = std::max(r.y1, r.y0);
    return r;
}

// A bound as the camera sees it: its normalised-device rectangle and its nearest clip w (the
// distance along the view axis for a perspective projection). `in_front` is false when part of
// it lies at or behind the eye plane, where the rectangle means nothing.
struct ScreenBound {
    bool in_front = false;
    double x0 = -1.0, y0 = -1.0, x1 = 1.0, y1 = 1.0;  // NDC
    double min_w = 0.0;
};

// Rule 5: whether a bound can be tested at all: wholly in front of the eye plane and farther than
// `near_w` (the near plane's clip w). NaN anywhere makes it untestable.
inline bool testable(const ScreenBound& b, double near_w) {
    return b.in_front && b.min_w > near_w && std::isfinite(b.x0) && std::isfinite(b.y0) &&
           std::isfinite(b.x1) && std::isfinite(b.y1);
}

// The 8 corners of [lo, hi] under `view_projection` (any clip convention with w the view
// depth): the rectangle of their projections, which holds the box's, and the least w, which is a
// corner's (w is linear).
inline ScreenBound projectBox(const glm::dmat4& view_projection, const glm::dvec3& lo,
                              const glm::dvec3& hi) {
    ScreenBound b;
    b.in_front = true;
    b.x0 = b.y0 = INFINITY;
    b.x1 = b.y1 = -INFINITY;
    b.min_w = INFINITY;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec4 p((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z,
                           1.0);
        const glm::dvec4 clip = view_projection * p;
        b.min_w = std::min(b.min_w, clip.w);
        if (!(clip.w > 0.0)) {
            b.in_front = false;
            continue;
        }
        b.x0 = std::min(b.x0, clip.x / clip.w);
        b.x1 = std::max(b.x1, clip.x / clip.w);
        b.y0 = std::min(b.y0, clip.y / clip.w);
        b.y1 = std::max(b.y1, clip.y / clip.w);
    }
    return b;
}

// The sphere (centre, radius) under `view_projection`: its exact projected rectangle (the planes
// through the eye tangent to the sphere, after Mara & McGuire 2013, solved here in clip space so
// that any perspective matrix serves: x_ndc = t where the plane (row0 - t row3) . p = 0 touches
// the sphere) and its least w.
inline ScreenBound projectSphere(const glm::dmat4& view_projection, const glm::dvec3& centre,
                                 double radius) {
    const auto row = [&](int r) {
        return glm::dvec4(view_projection[0][r], view_projection[1][r], view_projection[2][r],
                          view_projection[3][r]);
    };
    const glm::dvec4 c(centre, 1.0);
    const glm::dvec4 w_row = row(3);
    const glm::dvec3 beta(w_row);
    const double B = glm::dot(w_row, c);
    const double r2 = radius * radius;
    ScreenBound b;
    b.min_w = B - radius * glm::length(beta);
    b.in_front = b.min_w > 0.0;
    if (!b.in_front) return b;
    const double denom = B * B - r2 * glm::dot(beta, beta);  // > 0 when in front
    const auto range = [&](int r, double& lo, double& hi) {
        const glm::dvec4 a_row = row(r);
        const glm::dvec3 alpha(a_row);
        const double A = glm::dot(a_row, c);
        const double half_b = A * B - r2 * glm::dot(alpha, beta);
        const double cc = A * A - r2 * glm::dot(alpha, alpha);
        const double root = std::sqrt(std::max(0.0, half_b * half_b - denom * cc));
        lo = (half_b - root) / denom;
        hi = (half_b + root) / denom;
    };
    range(0, b.x0, b.x1);
    range(1, b.y0, b.y1);
    return b;
}

// The rectangle of a ScreenBound in window coordinates (x from 0 to width) as pixels touched.
inline TexelRect pixelsOf(const ScreenBound& b, uint32_t width, uint32_t height) {
    const double w = width, h = height;
    return pixelsTouched((b.x0 + 1.0) * 0.5 * w, (b.y0 + 1.0) * 0.5 * h, (b.x1 + 1.0) * 0.5 * w,
                         (b.y1 + 1.0) * 0.5 * h, width, height);
}

}  // namespace occsim::hzb
