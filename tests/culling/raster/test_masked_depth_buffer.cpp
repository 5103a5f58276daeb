// The masked software depth buffer (occsim/culling/raster/masked_depth_buffer.h): one test per
// conservativeness rule, each built so that breaking the rule makes it fail.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <iostream>

#include "masked_scenes.h"

namespace occsim {
namespace {

using namespace testing;

// The rule tests' camera: at the origin looking down -z, 90 degrees, square pixels. A point at
// view depth d shows at viewport pixel (px, py) when x = (2 px / W - 1) d aspect and
// y = (2 py / H - 1) d.
struct Screen {
    uint32_t width, height;
    double aspect() const { return static_cast<double>(width) / height; }
    float x(double px, double d) const {
        return static_cast<float>((2.0 * px / width - 1.0) * d * aspect());
    }
    float y(double py, double d) const { return static_cast<float>((2.0 * py / height - 1.0) * d); }
    CullView view(double near = 0.1) const {
        return cameraView({0, 0, 0}, {0, 0, -1}, width, height, near);
    }
};

// A wall at view depth d over the viewport rectangle [x0, x1] x [y0, y1] (pixels).
void wall(MaskedDepthBuffer& buffer, const Screen& s, double x0, double x1, double y0, double y1,
          double d) {
    const glm::vec3 a(s.x(x0, d), s.y(y0, d), -d), b(s.x(x1, d), s.y(y0, d), -d);
    const glm::vec3 c(s.x(x1, d), s.y(y1, d), -d), e(s.x(x0, d), s.y(y1, d), -d);
    const glm::vec3 corners[4] = {a, b, c, e};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    buffer.rasteriseMesh(corners, indices, glm::mat4(1.0f), edgeNeighbours(indices));
}

// A box 1 mm deep whose near face at view depth d shows over [x0, x1] x [y0, y1] (pixels).
Aabb card(const Screen& s, double x0, double x1, double y0, double y1, double d) {
    return makeAabb(glm::vec3(s.x(x0, d), s.y(y0, d), static_cast<float>(-d - 0.001)),
                    glm::vec3(s.x(x1, d), s.y(y1, d), static_cast<float>(-d)));
}

MaskedDepthBuffer beginBuffer(const Screen& s, uint32_t max_width,
                              MaskedKernel kernel = MaskedKernel::Plain, double near = 0.1,
                              const MaskedLayout& layout = {}) {
    MaskedDepthBuffer buffer(kernel, layout);
    const CullView v = s.view(near);
    buffer.beginFrame(v.view_projection, v.eye, s.width, s.height, max_width);
    return buffer;
}

TEST(MaskedDepthBuffer, AWallHidesWhatIsBehindItAndNotWhatIsBeside) {
    const Screen s{64, 32};
    MaskedDepthBuffer buffer = beginBuffer(s, 64);
    wall(buffer, s, -10, 40, -10, 50, 10.0);
    EXPECT_FALSE(buffer.testBox(card(s, 5, 30, 5, 25, 20.0)));
    EXPECT_TRUE(buffer.testBox(card(s, 35, 50, 5, 25, 20.0)));  // reaches past the wall's edge
    EXPECT_TRUE(buffer.testBox(card(s, 5, 30, 5, 25, 5.0)));    // in front of it
}

// Rule: a pixel is covered only when its centre lies inside every edge with room to spare
// (kCoverageMarginPx): a rasteriser's snapping may leave a centre 0.01 pixel inside uncovered.
TEST(MaskedDepthBuffer, AnEdgeBarelyPastAPixelCentreDoesNotCoverIt) {
    const Screen s{64, 16};
    MaskedDepthBuffer buffer = beginBuffer(s, 64, MaskedKernel::Plain, 0.1, everyPixel());
    wall(buffer, s, -100, 20.51, -100, 100, 10.0);  // pixel 20's centre (20.5) 0.01 inside
    EXPECT_TRUE(buffer.testBox(card(s, 20.4, 20.6, 4.4, 4.6, 20.0)));
    EXPECT_FALSE(buffer.testBox(card(s, 18.4, 18.6, 4.4, 4.6, 20.0)));
}

// Rule: at a coarse resolution a buffer pixel is covered only when every viewport pixel centre
// in its k x k block is covered, not its own centre alone.
TEST(MaskedDepthBuffer, ACoarsePixelIsCoveredOnlyWhenEveryPixelCentreInItIs) {
    const Screen s{64, 16};
    MaskedDepthBuffer buffer = beginBuffer(s, 32, MaskedKernel::Plain, 0.1, everyPixel());
    ASSERT_EQ(buffer.pixelSize(), 2u);
    // Buffer pixel 10 holds viewport columns 20 and 21 (centres 20.5, 21.5; block centre 21):
    // the wall's edge at 21.3 covers the block's centre and column 20, not column 21.
    wall(buffer, s, -100, 21.3, -100, 100, 10.0);
    EXPECT_TRUE(buffer.testBox(card(s, 21.4, 21.6, 4.4, 4.6, 20.0)));
    EXPECT_FALSE(buffer.testBox(card(s, 16.4, 17.6, 4.4, 4.6, 20.0)));
}

// Rule: a tile keeps a triangle's farthest depth over the part of the tile it covers.
TEST(MaskedDepthBuffer, ASlopedOccludersTileDepthIsItsFarthestPoint) {
    const Screen s{32, 32};
    MaskedDepthBuffer buffer = beginBuffer(s, 32);
    // The plane w = 20 + x/2: depth 13.3 at the left edge of the view, 40 at the right.
    const glm::vec3 corners[4] = {{-30, -100, -5}, {60, -100, -50}, {60, 100, -50}, {-30, 100, -5}};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    buffer.rasteriseMesh(corners, indices, glm::mat4(1.0f), edgeNeighbours(indices));
    // At pixel column 28 the plane lies at depth 32.8: a card at 31 is in front of it.
    EXPECT_TRUE(buffer.testBox(card(s, 28.4, 28.6, 16.4, 16.6, 31.0)));
    EXPECT_FALSE(buffer.testBox(card(s, 28.4, 28.6, 16.4, 16.6, 45.0)));
}

// Rule: merging into the working layer keeps the farther of its depth and the triangle's; a
// full mask makes that depth the tile's reference.
TEST(MaskedDepthBuffer, MergingKeepsTheFartherDepth) {
    const Screen s{32, 8};
    MaskedDepthBuffer buffer = beginBuffer(s, 32, MaskedKernel::Plain, 0.1, everyPixel(32, 8));
    wall(buffer, s, -10, 16.0, -10, 20, 10.0);  // left half at 10
    wall(buffer, s, 16.0, 50, -10, 20, 20.0);   // right half at 20: the tile is full
    EXPECT_TRUE(buffer.testBox(card(s, 2, 30, 1, 7, 15.0)));
    EXPECT_FALSE(buffer.testBox(card(s, 2, 30, 1, 7, 25.0)));
}

// Rule: when a much nearer triangle replaces the working layer, the pixels it leaves fall back
// to the reference depth; they keep no claim to the new, nearer depth.
TEST(MaskedDepthBuffer, ReplacingTheWorkingLayerDropsTheOldPixelsToTheReference) {
    const Screen s{32, 8};
    MaskedDepthBuffer buffer = beginBuffer(s, 32, MaskedKernel::Plain, 0.1, everyPixel(32, 8));
    wall(buffer, s, -10, 16.0, -10, 20, 20.0);                  // left half at 20
    wall(buffer, s, 16.0, 50, -10, 20, 2.0);                    // right half much nearer, at 2
    EXPECT_TRUE(buffer.testBox(card(s, 2, 12, 1, 7, 10.0)));    // in front of the wall at 20
    EXPECT_FALSE(buffer.testBox(card(s, 20, 30, 1, 7, 10.0)));  // behind the wall at 2
}

// Rule: triangles are clipped at (a little beyond) the near plane: what a rasteriser clips away
// hides nothing. A floor 0.5 m below the eye meets the bottom rows nearer than the near plane.
TEST(MaskedDepthBuffer, WhatLiesInFrontOfTheNearPlaneHidesNothing) {
    const Screen s{32, 32};
    MaskedDepthBuffer buffer = beginBuffer(s, 32, MaskedKernel::Plain, 1.0);
    const glm::vec3 corners[4] = {
        {-100, -0.5f, 10}, {100, -0.5f, 10}, {100, -0.5f, -100}, {-100, -0.5f, -100}};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    buffer.rasteriseMesh(corners, indices, glm::mat4(1.0f), edgeNeighbours(indices));
    EXPECT_TRUE(buffer.testBox(card(s, 15.4, 15.6, 0.4, 0.6, 5.0)));  // below the clipped part
    // Below the floor proper (beyond its far end: the tile keeps its farthest depth, 100 m).
    EXPECT_FALSE(buffer.testBox(card(s, 15.4, 15.6, 12.4, 12.6, 120.0)));
}

// Rule: a box whose nearest point is at or behind the eye is visible (its projection means
// nothing), even behind a wall that fills the view.
TEST(MaskedDepthBuffer, ABoxReachingBehindTheEyeIsVisible) {
    const Screen s{32, 32};
    MaskedDepthBuffer buffer = beginBuffer(s, 32);
    wall(buffer, s, -100, 100, -100, 100, 10.0);
    EXPECT_TRUE(
        buffer.testBox(makeAabb(glm::vec3(-0.1f, -0.1f, -20.0f), glm::vec3(0.1f, 0.1f, 1.0f))));
    EXPECT_FALSE(buffer.testBox(card(s, 10, 20, 10, 20, 20.0)));
}

// Rule: ties are visible: a box whose near face lies on the occluder is not hidden by it (the
// stored depth is made farther and the box's nearer, by kDepthMargin and by the rounding bound;
// either alone keeps this test passing, without both it fails).
TEST(MaskedDepthBuffer, ABoxOnTheOccludersSurfaceIsVisible) {
    const Screen s{32, 32};
    MaskedDepthBuffer buffer = beginBuffer(s, 32);
    wall(buffer, s, -100, 100, -100, 100, 10.0);
    EXPECT_TRUE(buffer.testBox(card(s, 10, 20, 10, 20, 10.0)));
    EXPECT_FALSE(buffer.testBox(card(s, 10, 20, 10, 20, 10.01)));
}

// Rule: a box's rectangle is grown by kBoxMarginPx before it is rounded to pixel centres: its
// own triangles, snapped, may reach a centre 0.002 pixel outside it.
TEST(MaskedDepthBuffer, ABoxsRectangleIsGrownBeforeRounding) {
    const Screen s{64, 16};
    MaskedDepthBuffer buffer = beginBuffer(s, 64, MaskedKernel::Plain, 0.1, everyPixel());
    wall(buffer, s, 21.0, 100, -100, 100, 10.0);  // covers column 21 on, not column 20
    EXPECT_TRUE(buffer.testBox(card(s, 20.502, 22, 4.4, 4.6, 20.0)));
    EXPECT_FALSE(buffer.testBox(card(s, 21.3, 22, 4.4, 4.6, 20.0)));
}

// Rule: pixels past the viewport's edge count as covered only where there are no pixels: the
// last tile column and row of an odd viewport (33 x 9) flush only when their real pixels are.
TEST(MaskedDepthBuffer, AnOddViewportsEdgeTilesFlushOnlyOverTheirOwnPixels) {
    const Screen s{33, 9};
    {
        MaskedDepthBuffer buffer = beginBuffer(s, 64);
        ASSERT_EQ(buffer.tilesAcross(), 2u);
        wall(buffer, s, -10, 100, -10, 4.0, 10.0);  // rows 0-3 of every column
        EXPECT_TRUE(buffer.testBox(card(s, 32.4, 32.6, 6.4, 6.6, 20.0)));  // column 32, row 6
        EXPECT_FALSE(buffer.testBox(card(s, 32.4, 32.6, 2.4, 2.6, 20.0)));
    }
    {
        MaskedDepthBuffer buffer = beginBuffer(s, 64);
        wall(buffer, s, -10, 16.0, -10, 100, 10.0);  // columns 0-15 of every row
        EXPECT_TRUE(buffer.testBox(card(s, 20.4, 20.6, 8.4, 8.6, 20.0)));  // row 8, column 20
        EXPECT_FALSE(buffer.testBox(card(s, 10.4, 10.6, 8.4, 8.6, 20.0)));
    }
}

// Rule: an edge goes without the coverage margin only when the one triangle sharing it lies on
// its other side on screen. Folded back over its neighbour (as a closed mesh's front and back
// faces meet at its silhouette), the edge keeps its margin.
TEST(MaskedDepthBuffer, AFoldedEdgeKeepsItsMargin) {
    const Screen s{64, 16};
    const double d = 10.0;
    const glm::vec3 corners[4] = {{s.x(20.51, d), s.y(-100, d), static_cast<float>(-d)},
                                  {s.x(20.51, d), s.y(100, d), static_cast<float>(-d)},
                                  {s.x(-100, d), s.y(8, d), static_cast<float>(-d)},
                                  {s.x(-50, d), s.y(8, d), static_cast<float>(-d - 1)}};
    const uint32_t folded[6] = {0, 1, 2, 1, 0, 3};
    MaskedDepthBuffer buffer = beginBuffer(s, 64);
    buffer.rasteriseMesh(corners, folded, glm::mat4(1.0f), edgeNeighbours(folded));
    EXPECT_TRUE(buffer.testBox(card(s, 20.4, 20.6, 8.4, 8.6, 20.0)));
    EXPECT_FALSE(buffer.testBox(card(s, 15.4, 15.6, 8.4, 8.6, 20.0)));
}

// Rule: each cell keeps its own two depths. Two walls at 10 m and 30 m share a 32x8 tile: with
// 8x4 cells the near wall's cells hide what lies at 20 m behind it; one cell per tile (32x8) can
// only keep the farther wall's depth once the tile is full.
TEST(MaskedDepthBuffer, EachCellKeepsItsOwnDepths) {
    const Screen s{32, 8};
    for (const uint32_t cell_width : {8u, 32u}) {
        MaskedLayout layout;
        layout.cell_width = cell_width;
        layout.cell_height = cell_width == 8 ? 4 : 8;
        MaskedDepthBuffer buffer = beginBuffer(s, 32, MaskedKernel::Plain, 0.1, layout);
        wall(buffer, s, -10, 8.0, -10, 20, 10.0);  // columns 0-7
        wall(buffer, s, 8.0, 50, -10, 20, 30.0);   // columns 8-31
        EXPECT_EQ(buffer.testBox(card(s, 1, 6, 1, 7, 20.0)), cell_width == 32) << cell_width;
        EXPECT_FALSE(buffer.testBox(card(s, 1, 30, 1, 7, 40.0))) << cell_width;
        EXPECT_TRUE(buffer.testBox(card(s, 10, 30, 1, 7, 20.0))) << cell_width;
    }
}

// Rule: boxes are tested against the reference layer only unless asked otherwise: a wall that
// covers part of a cell hides nothing there until the cell is full.
TEST(MaskedDepthBuffer, OnlyTheReferenceLayerHidesUnlessTheWorkingLayerIsAsked) {
    const Screen s{32, 8};
    for (const bool working : {false, true}) {
        MaskedLayout layout;
        layout.test_working_layer = working;
        MaskedDepthBuffer buffer = beginBuffer(s, 32, MaskedKernel::Plain, 0.1, layout);
        wall(buffer, s, -10, 4.0, -10, 20, 10.0);  // columns 0-3: half of each left cell
        EXPECT_EQ(buffer.testBox(card(s, 1, 3, 1, 3, 20.0)), !working) << working;
        EXPECT_TRUE(buffer.testBox(card(s, 1, 6, 1, 3, 20.0))) << working;
    }
}

// Rule (the paper's quick merge): a triangle much nearer than the working layer discards it; the
// old pixels fall back to the reference depth. Within one 8x4 cell: columns 0-3 at 20 m, then
// columns 4-7 at 2 m; what lies at 10 m behind columns 0-3 stays visible, behind 4-7 hidden.
TEST(MaskedDepthBuffer, ANearTriangleDiscardsTheWorkingLayerOfItsCell) {
    const Screen s{32, 8};
    for (const bool accurate : {false, true}) {
        MaskedLayout layout = everyPixel();
        layout.merge = accurate ? MaskedMerge::Accurate : MaskedMerge::Quick;
        MaskedDepthBuffer buffer = beginBuffer(s, 32, MaskedKernel::Plain, 0.1, layout);
        wall(buffer, s, -10, 4.0, -10, 4.0, 20.0);
        wall(buffer, s, 4.0, 8.0, -10, 4.0, 2.0);
        EXPECT_TRUE(buffer.testBox(card(s, 1, 3, 1, 3, 10.0))) << accurate;
        EXPECT_FALSE(buffer.testBox(card(s, 5, 7, 1, 3, 10.0))) << accurate;
    }
}

// Rule (the accurate merge): of merging, replacing and dropping, the cell keeps the outcome with
// the nearest bounds in sum. A wall at 10 m over half a 32x8 cell, then a wall at 100 m over
// the other half: the quick rule merges (the cell's reference becomes 100 m everywhere); the
// accurate merge drops the far wall and keeps 10 m over the near half.
TEST(MaskedDepthBuffer, TheAccurateMergeKeepsANearLayerAFarTriangleWouldDragBack) {
    const Screen s{32, 8};
    for (const bool accurate : {false, true}) {
        MaskedLayout layout = everyPixel(32, 8);
        layout.merge = accurate ? MaskedMerge::Accurate : MaskedMerge::Quick;
        MaskedDepthBuffer buffer = beginBuffer(s, 32, MaskedKernel::Plain, 0.1, layout);
        wall(buffer, s, -10, 16.0, -10, 20, 10.0);
        wall(buffer, s, 16.0, 50, -10, 20, 100.0);
        EXPECT_EQ(buffer.testBox(card(s, 2, 12, 1, 7, 50.0)), !accurate) << accurate;
        EXPECT_EQ(buffer.testBox(card(s, 20, 30, 1, 7, 150.0)), accurate) << accurate;
    }
}

TEST(MaskedDepthBuffer, RefusesACellItCannotKeep) {
    EXPECT_EQ(validMaskedLayout(MaskedLayout{}), "");
    for (const auto& [w, h] : {std::pair{12u, 4u}, {8u, 2u}, {64u, 8u}, {4u, 4u}}) {
        MaskedLayout layout;
        layout.cell_width = w;
        layout.cell_height = h;
        EXPECT_NE(validMaskedLayout(layout), "") << w << "x" << h;
        EXPECT_THROW(MaskedDepthBuffer(MaskedKernel::Plain, layout), std::invalid_argument);
    }
    const CullerRow* t = findCuller("masked");
    ASSERT_NE(t, nullptr);
    OptionValues values(t->options);
    values.set("cell_width", 12);
    EXPECT_NE(checkOptionValues(*t, values).find("cell_width"), std::string::npos);
}

// Rule: an edge shared by position goes without margin once the mesh is welded
// (weldedIndices): a wall of two triangles that repeat their diagonal's vertices (as meshes do
// where normals differ) leaks along the diagonal unwelded, and hides what is behind it welded.
TEST(MaskedDepthBuffer, ASeamOfRepeatedVerticesIsWeldedShut) {
    const Screen s{32, 32};
    const double d = 10.0;
    const glm::vec3 a(s.x(-4, d), s.y(-4, d), -d), b(s.x(36, d), s.y(-4, d), -d);
    const glm::vec3 c(s.x(36, d), s.y(36, d), -d), e(s.x(-4, d), s.y(36, d), -d);
    const glm::vec3 corners[6] = {a, b, c, a, c, e};  // each triangle its own vertices
    const uint32_t indices[6] = {0, 1, 2, 3, 4, 5};
    for (const bool weld : {false, true}) {
        MaskedDepthBuffer buffer = beginBuffer(s, 32);
        const std::vector<uint32_t> welded =
            weld ? weldedIndices(corners, indices) : std::vector<uint32_t>(indices, indices + 6);
        buffer.rasteriseMesh(corners, welded, glm::mat4(1.0f), edgeNeighbours(welded));
        EXPECT_EQ(buffer.testBox(card(s, 2, 30, 2, 30, 20.0)), !weld) << weld;
    }
    const std::vector<uint32_t> welded = weldedIndices(corners, indices);
    EXPECT_EQ(welded, (std::vector<uint32_t>{0, 1, 2, 0, 2, 5}));
}

// An orthographic view (a light's): looking down -z from `at`, 20 m across, depth 1 to 50 m.
// A wall 10 m down hides what lies behind it, not what is beside it or in front of it; a box
// reaching through the near plane or past the far one is seen as a real rasteriser would; the
// same 1 km from the origin. (A scene 10^6 m out is culled relative to its culling origin:
// ShadowStress.AMillionMetresFromTheOriginTheShadowPassIsTheSame runs masked in the light's view
// there.)
TEST(MaskedDepthBuffer, AnOrthographicViewHidesWhatIsBehindAWallAndNotWhatIsBesideOrInFront) {
    for (const glm::dvec3 at : {glm::dvec3(0.0), glm::dvec3(1e3, 0.0, -1e3)}) {
        const glm::dmat4 view_projection =
            glm::ortho(-10.0, 10.0, -10.0, 10.0, 1.0, 50.0) *
            glm::lookAt(at, at + glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
        MaskedDepthBuffer buffer;
        buffer.beginOrthographicFrame(glm::mat4(view_projection), 64, 64, 64);
        ASSERT_TRUE(buffer.active());
        const glm::vec3 o(at);
        auto box = [&](glm::vec3 lo, glm::vec3 hi) { return makeAabb(o + lo, o + hi); };
        // A square wall 10 m down, 10 m across, 1 mm thick... as two triangles.
        const glm::vec3 corners[4] = {o + glm::vec3(-5, -5, -10), o + glm::vec3(5, -5, -10),
                                      o + glm::vec3(5, 5, -10), o + glm::vec3(-5, 5, -10)};
        const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
        buffer.rasteriseMesh(corners, indices, glm::mat4(1.0f), edgeNeighbours(indices));
        const std::string where = at.x == 0.0 ? "at the origin" : "1 km out";
        EXPECT_FALSE(buffer.testBox(box({-3, -3, -21}, {3, 3, -20}))) << where;
        EXPECT_FALSE(buffer.testBox(box({-3, -3, -60}, {3, 3, -45})))
            << where << ": behind the wall, reaching past the far plane";
        EXPECT_TRUE(buffer.testBox(box({3, -3, -21}, {7, 3, -20}))) << where << ": past its edge";
        EXPECT_TRUE(buffer.testBox(box({-3, -3, -6}, {3, 3, -5}))) << where << ": in front";
        EXPECT_TRUE(buffer.testBox(box({-3, -3, -10.5f}, {3, 3, -9.99f})))
            << where << ": through the wall";
        EXPECT_TRUE(buffer.testBox(box({-3, -3, -20}, {3, 3, 0})))
            << where << ": through the near plane";
    }
}

// In an orthographic view depth is affine across the screen: a wall sloping from 10 m down at
// x = -5 to 30 m down at x = 5 is 20 m down in the middle. A box 19.8 m down there, just in front
// of it, is visible (a depth interpolated as if it were not affine, such as a 1/w of a w linear
// in the depth, puts the wall about 2 m nearer there and hides it: checked by mutation); one
// behind the farthest point of the depth cells it touches (0.625 m wide: 21.25 m down) is hidden;
// a triangle past the far plane hides nothing.
TEST(MaskedDepthBuffer, AnOrthographicViewsDepthIsAffineAcrossTheScreen) {
    const glm::dmat4 view_projection =
        glm::ortho(-10.0, 10.0, -10.0, 10.0, 1.0, 50.0) *
        glm::lookAt(glm::dvec3(0.0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
    MaskedDepthBuffer buffer;
    buffer.beginOrthographicFrame(glm::mat4(view_projection), 256, 256, 256);
    const glm::vec3 corners[4] = {{-5, -5, -10}, {5, -5, -30}, {5, 5, -30}, {-5, 5, -10}};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    buffer.rasteriseMesh(corners, indices, glm::mat4(1.0f), edgeNeighbours(indices));
    EXPECT_TRUE(
        buffer.testBox(makeAabb(glm::vec3(-0.05f, -1, -19.9f), glm::vec3(0.05f, 1, -19.8f))));
    EXPECT_FALSE(buffer.testBox(makeAabb(glm::vec3(-0.05f, -1, -23), glm::vec3(0.05f, 1, -22))));

    MaskedDepthBuffer far;
    far.beginOrthographicFrame(glm::mat4(view_projection), 64, 64, 64);
    far.rasteriseTriangle({-9, -9, -55}, {9, -9, -55}, {0, 9, -55});
    EXPECT_TRUE(far.testBox(makeAabb(glm::vec3(-1, -1, -70), glm::vec3(1, 1, -60))));
    EXPECT_EQ(far.stats().triangles_rasterised, 0u);
    // A perspective matrix is not orthographic: the buffer stays off.
    MaskedDepthBuffer perspective;
    perspective.beginOrthographicFrame(cameraView({0, 0, 0}, {0, 0, -1}, 64, 64).view_projection,
                                       64, 64, 64);
    EXPECT_FALSE(perspective.active());
}

TEST(MaskedDepthBuffer, WithoutAPerspectiveCameraEverythingIsVisible) {
    MaskedDepthBuffer buffer;
    buffer.beginFrame(glm::mat4(1.0f), glm::vec3(0.0f), 64, 64, 64);
    EXPECT_FALSE(buffer.active());
    buffer.rasteriseTriangle({-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
    EXPECT_TRUE(buffer.testBox(makeAabb(glm::vec3(0.0f), glm::vec3(0.1f))));
    buffer.beginFrame(cameraView({0, 0, 0}, {0, 0, -1}, 64, 64).view_projection, {}, 0, 64, 64);
    EXPECT_TRUE(buffer.testBox(makeAabb(glm::vec3(0.0f), glm::vec3(0.1f))));
}

}  // namespace
}  // namespace occsim
