// Boxes drawn as wireframes through a frame's camera (sim/output/box_wireframe.h): where the box
// projects and nowhere else, nothing behind the eye, edges cut at the near plane, nothing for a
// box that is not finite, and the same picture for a box given relative to a culling origin far
// from the world's.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "overlay_view.h"
#include "sim/output/box_wireframe.h"

namespace occsim {
namespace {

using testing::kOverlayNear;
using testing::kOverlaySize;
using testing::overlayView;
using testing::pixelsOf;

constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kGreen{0, 255, 0};

RasterCanvas canvasWith(const ViewSetup& view, const Aabb& box) {
    RasterCanvas canvas(kOverlaySize, kOverlaySize, kBlack);
    drawBoxWireframe(canvas, view, kOverlayNear, box, kGreen);
    return canvas;
}

TEST(BoxWireframe, ABoxAheadIsOutlinedWhereItProjectsAndNowhereElse) {
    // A 2 m cube 10 m ahead, seen through 90 degrees on 64 pixels: its front face spans
    // 64 * 2 / (2 * 9) = 7 pixels around the centre, its back face 6.
    const RasterCanvas canvas = canvasWith(overlayView(), Aabb{{-1, -1, -11}, {1, 1, -9}});
    EXPECT_GT(pixelsOf(canvas, kGreen), 40u);
    for (uint32_t y = 0; y < kOverlaySize; ++y) {
        for (uint32_t x = 0; x < kOverlaySize; ++x) {
            if (canvas.at(static_cast<int>(x), static_cast<int>(y)) != kGreen) continue;
            EXPECT_LT(std::abs(static_cast<int>(x) - 32), 6) << x << "," << y;
            EXPECT_LT(std::abs(static_cast<int>(y) - 32), 6) << x << "," << y;
        }
    }
}

TEST(BoxWireframe, ABoxBehindTheEyeDrawsNothingAndOneThroughTheNearPlaneIsCut) {
    EXPECT_EQ(pixelsOf(canvasWith(overlayView(), Aabb{{-1, -1, 5}, {1, 1, 7}}), kGreen), 0u);
    // From 5 m ahead to 5 m behind: the edges along z are cut at the near plane and run out of
    // the picture; the far face is drawn whole.
    const RasterCanvas through = canvasWith(overlayView(), Aabb{{-1, -1, -5}, {1, 1, 5}});
    EXPECT_GT(pixelsOf(through, kGreen), 20u);
}

TEST(BoxWireframe, ABoxThatIsNotFiniteDrawsNothing) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(pixelsOf(canvasWith(overlayView(), Aabb{{-1, nan, -11}, {1, 1, -9}}), kGreen), 0u);
    EXPECT_EQ(pixelsOf(canvasWith(overlayView(), Aabb{}), kGreen), 0u) << "an empty box";
}

TEST(BoxWireframe, BoxesAreInTheCullingFrameFarFromTheWorldsOrigin) {
    // The camera 10^6 m away; the box given relative to a culling origin beside it.
    const glm::dvec3 far{1.0e6, 2.0, -1.0e6};
    const Aabb box{{-1, -1, -11}, {1, 1, -9}};
    const RasterCanvas here = canvasWith(overlayView(), box);
    const RasterCanvas there = canvasWith(overlayView(far, far), box);
    for (uint32_t y = 0; y < kOverlaySize; ++y) {
        for (uint32_t x = 0; x < kOverlaySize; ++x)
            EXPECT_EQ(there.at(static_cast<int>(x), static_cast<int>(y)) == kGreen,
                      here.at(static_cast<int>(x), static_cast<int>(y)) == kGreen)
                << x << "," << y;
    }
}

}  // namespace
}  // namespace occsim
