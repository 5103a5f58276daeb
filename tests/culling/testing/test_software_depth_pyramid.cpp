// The conservativeness rules of occsim/culling/geometry/hzb_rules.h one by one (each test fails
// when its rule is broken) and the software pyramid of the CPU test devices
// (occsim/culling/testing/software_depth_pyramid.h) against the exact depth raster.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <string>

#include "culling/cullers/hzb_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/geometry/hzb_rules.h"
#include "occsim/culling/testing/depth_raster_device.h"
#include "occsim/culling/testing/scripted_query_device.h"
#include "occsim/culling/testing/software_depth_pyramid.h"

namespace occsim {
namespace {

using hzb::TexelRect;

// --- Rule 1: the base and what each texel covers -------------------------------------------------

TEST(HzbRules, TheBaseIsThePowerOfTwoAtOrBelowTheViewport) {
    EXPECT_EQ(hzb::pyramidBaseSize(0), 1u);
    EXPECT_EQ(hzb::pyramidBaseSize(1), 1u);
    EXPECT_EQ(hzb::pyramidBaseSize(2), 2u);
    EXPECT_EQ(hzb::pyramidBaseSize(3), 2u);
    EXPECT_EQ(hzb::pyramidBaseSize(640), 512u);
    EXPECT_EQ(hzb::pyramidBaseSize(1024), 1024u);
    EXPECT_EQ(hzb::pyramidBaseSize(1025), 1024u);
    EXPECT_EQ(hzb::pyramidLevelCount(512, 256), 10u);  // 512 .. 1
    EXPECT_EQ(hzb::levelSize(256, 9), 1u);
}

// Each texel covers every pixel its area overlaps (up to 3 per axis when the viewport is not a
// power of two), and nothing else: checked against the areas in double for every size to 300.
TEST(HzbRules, EachBaseTexelCoversEveryPixelItsAreaOverlaps) {
    for (uint32_t viewport = 1; viewport <= 300; ++viewport) {
        const uint32_t base = hzb::pyramidBaseSize(viewport);
        const double scale = double(viewport) / base;
        for (uint32_t t = 0; t < base; ++t) {
            const double lo = t * scale, hi = (t + 1) * scale;
            uint32_t first = viewport, last = 0;
            for (uint32_t p = 0; p < viewport; ++p) {
                if (p < hi && p + 1 > lo) {
                    first = std::min(first, p);
                    last = std::max(last, p);
                }
            }
            ASSERT_EQ(hzb::firstCovered(t, viewport, base), first) << viewport << " texel " << t;
            ASSERT_EQ(hzb::lastCovered(t, viewport, base), last) << viewport << " texel " << t;
            ASSERT_LE(last - first + 1, 3u);
        }
        // The inverse: the texels said to cover pixel p do cover it.
        for (uint32_t p = 0; p < viewport; ++p) {
            for (uint32_t t = hzb::firstCovering(p, viewport, base);
                 t <= hzb::lastCovering(p, viewport, base); ++t) {
                ASSERT_LE(hzb::firstCovered(t, viewport, base), p);
                ASSERT_GE(hzb::lastCovered(t, viewport, base), p);
            }
        }
    }
}

// --- Rule 2: each texel holds the farthest depth below it ----------------------------------------

// Random depths on viewports of odd sizes: every texel of every level is the largest distance of
// the pixels its area overlaps, computed from the areas in double.
TEST(HzbRules, EveryTexelHoldsTheFarthestDepthOfThePixelsItCovers) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> depth(1.0f, 100.0f);
    for (const auto& [w, h] : {std::pair{67u, 45u}, {129u, 3u}, {1u, 17u}, {96u, 64u}}) {
        std::vector<float> raster(size_t{w} * h);
        for (float& d : raster) d = depth(rng);
        SoftwareDepthPyramid pyramid;
        pyramid.build(raster, w, h);
        for (uint32_t l = 0; l < pyramid.levelCount(); ++l) {
            const uint32_t lw = pyramid.levelWidth(l), lh = pyramid.levelHeight(l);
            const double sx = double(w) / lw, sy = double(h) / lh;
            for (uint32_t ty = 0; ty < lh; ++ty) {
                for (uint32_t tx = 0; tx < lw; ++tx) {
                    float farthest = 0.0f;
                    for (uint32_t y = 0; y < h; ++y) {
                        if (!(y < (ty + 1) * sy && y + 1 > ty * sy)) continue;
                        for (uint32_t x = 0; x < w; ++x) {
                            if (x < (tx + 1) * sx && x + 1 > tx * sx) {
                                farthest = std::max(farthest, raster[size_t{y} * w + x]);
                            }
                        }
                    }
                    ASSERT_EQ(pyramid.texel(l, tx, ty), farthest)
                        << w << "x" << h << " level " << l << " texel " << tx << "," << ty;
                }
            }
        }
    }
}

// --- Rule 3: the level is rounded up -------------------------------------------------------------

// For every footprint in base texels, the level makes it span at most 2 texels per axis, and is the
// finest level that does. With floor(log2(extent)) instead, footprints of 3 texels appear.
TEST(HzbRules, TheLevelIsRoundedUpSoTheFootprintSpansAtMostTwoTexels) {
    for (uint32_t t0 = 0; t0 < 130; ++t0) {
        for (uint32_t t1 = t0; t1 < 260; ++t1) {
            const TexelRect base{t0, 0, t1, 0};
            const uint32_t level = hzb::pyramidLevelFor(base);
            const TexelRect f = hzb::footprintAt(base, level);
            ASSERT_LE(f.x1 - f.x0 + 1, 2u) << "texels " << t0 << ".." << t1 << " level " << level;
            if (level > 0) {
                // One level finer would need 3 texels for some placement of this extent.
                EXPECT_GT((t1 - t0 + 1), 1u << (level - 1));
            }
        }
    }
}

// --- Rule 4: every texel of the footprint is read ------------------------------------------------

// A footprint of 3x3 texels (what a level rounded down gives) whose only texel far enough to let
// the bound show is the last one: a reader that takes 2x2 from the corner culls it.
TEST(HzbRules, EveryTexelOfTheFootprintIsReadNotAFixedTwoByTwo) {
    const uint32_t w = 64, h = 64;
    std::vector<float> raster(size_t{w} * h, 1.0f);  // a near occluder everywhere ...
    raster[size_t{40} * w + 40] = 50.0f;             // ... but one far pixel at (40, 40)
    SoftwareDepthPyramid pyramid;
    pyramid.build(raster, w, h);
    // Level 3 (texels of 8 pixels): pixels 16..47 touch texels 2..5; take texels 3..5 at level
    // 3: three per axis, the far pixel in texel (5, 5).
    const TexelRect footprint{3, 3, 5, 5};
    EXPECT_TRUE(pyramid.mayShowAt(footprint, 3, 10.0f)) << "the far texel is the footprint's last";
    EXPECT_FALSE(pyramid.mayShowAt({3, 3, 4, 4}, 3, 10.0f)) << "the first 2x2 hide it";
    // And through the rules: a bound over pixels 16..47 at distance 10 may show.
    EXPECT_TRUE(pyramid.mayShow({16, 16, 47, 47}, 10.0f));
    EXPECT_FALSE(pyramid.mayShow({16, 16, 31, 31}, 10.0f)) << "the far pixel is outside";
}

// Random rectangles on random rasters of random sizes: whenever a pixel of the rectangle is not
// nearer than the bound (the exact buffer would let it show), the pyramid lets it show.
TEST(HzbRules, ThePyramidNeverHidesWhatTheExactBufferShows) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<uint32_t> size(1, 200);
    std::uniform_real_distribution<float> depth(1.0f, 100.0f);
    for (int trial = 0; trial < 200; ++trial) {
        const uint32_t w = size(rng), h = size(rng);
        std::vector<float> raster(size_t{w} * h);
        for (float& d : raster) d = depth(rng);
        SoftwareDepthPyramid pyramid;
        pyramid.build(raster, w, h);
        for (int r = 0; r < 50; ++r) {
            std::uniform_int_distribution<uint32_t> px(0, w - 1), py(0, h - 1);
            uint32_t x0 = px(rng), x1 = px(rng), y0 = py(rng), y1 = py(rng);
            if (x0 > x1) std::swap(x0, x1);
            if (y0 > y1) std::swap(y0, y1);
            const float nearest = depth(rng);
            bool exact = false;
            for (uint32_t y = y0; y <= y1 && !exact; ++y) {
                for (uint32_t x = x0; x <= x1 && !exact; ++x) {
                    exact = nearest <= raster[size_t{y} * w + x];
                }
            }
            if (exact) {
                ASSERT_TRUE(pyramid.mayShow({x0, y0, x1, y1}, nearest))
                    << w << "x" << h << " rect " << x0 << "," << y0 << ".." << x1 << "," << y1;
            }
        }
    }
}

// --- Projection ------------------------------------------------------------------------------

// The sphere's rectangle (solved in clip space) holds the projections of points on the sphere,
// and is tight: some point reaches each side.
TEST(HzbRules, TheProjectedSphereRectangleHoldsTheSphereAndIsTight) {
    const glm::dmat4 vp =
        glm::perspective(glm::radians(60.0), 1.5, 0.1, 1000.0) *
        glm::lookAt(glm::dvec3(1, 2, 3), glm::dvec3(0, 0, -20), glm::dvec3(0, 1, 0));
    std::mt19937 rng(3);
    std::normal_distribution<double> n(0.0, 1.0);
    const glm::dvec3 centre(2, -1, -15);
    const double radius = 3.0;
    const hzb::ScreenBound b = hzb::projectSphere(vp, centre, radius);
    ASSERT_TRUE(b.in_front);
    double x0 = 1e9, x1 = -1e9;
    for (int i = 0; i < 20000; ++i) {
        const glm::dvec3 p = centre + radius * glm::normalize(glm::dvec3(n(rng), n(rng), n(rng)));
        const glm::dvec4 clip = vp * glm::dvec4(p, 1.0);
        const double x = clip.x / clip.w, y = clip.y / clip.w;
        ASSERT_GE(x, b.x0 - 1e-9);
        ASSERT_LE(x, b.x1 + 1e-9);
        ASSERT_GE(y, b.y0 - 1e-9);
        ASSERT_LE(y, b.y1 + 1e-9);
        ASSERT_GE(clip.w, b.min_w - 1e-9);
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
    }
    EXPECT_NEAR(x0, b.x0, 0.01);
    EXPECT_NEAR(x1, b.x1, 0.01);
    // A sphere around the eye is not in front.
    EXPECT_FALSE(hzb::projectSphere(vp, glm::dvec3(1, 2, 3), 0.5).in_front);
}

}  // namespace
}  // namespace occsim
