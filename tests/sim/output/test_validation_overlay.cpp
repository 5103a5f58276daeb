// The validation overlay (sim/output/validation_overlay.h) on a made-up frame, without a run: a
// missed object's own pixels tinted red and its box in red, an object drawn while hidden as a
// yellow box, a culled one as a grey box, an object drawn and seen left alone; the legend's
// classes in drawing order. The viewer's picture on real frames:
// tests/sim/view/test_view_picture.cpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "overlay_view.h"
#include "sim/output/validation_overlay.h"

namespace occsim {
namespace {

using testing::kOverlayNear;
using testing::kOverlaySize;
using testing::overlayView;
using testing::pixelsOf;

constexpr Rgb kBackground{10, 10, 10};

// Four boxes in a row, 10 m ahead, apart on the canvas: object i at x = -6 + 4 i.
std::vector<Aabb> fourBoxes() {
    std::vector<Aabb> boxes;
    for (int i = 0; i < 4; ++i) {
        const float x = -6.0f + 4.0f * static_cast<float>(i);
        boxes.push_back(Aabb{{x - 1, -1, -11}, {x + 1, 1, -9}});
    }
    return boxes;
}

RasterCanvas overlaid(const std::vector<uint8_t>& verdicts, const std::vector<uint32_t>& ids) {
    RasterCanvas canvas(kOverlaySize, kOverlaySize, kBackground);
    const std::vector<Aabb> boxes = fourBoxes();
    ValidationInput in;
    in.verdicts = verdicts;
    in.object_boxes = boxes;
    in.truth_ids = ids;
    in.view = overlayView();
    in.near_m = kOverlayNear;
    drawValidationOverlay(canvas, in);
    return canvas;
}

TEST(ValidationOverlay, EachVerdictIsDrawnInItsColourAndDrawnVisibleIsLeftAlone) {
    const auto v = [](ObjectVerdict verdict) { return static_cast<uint8_t>(verdict); };
    const std::vector<uint8_t> verdicts = {v(ObjectVerdict::Missed), v(ObjectVerdict::DrawnHidden),
                                           v(ObjectVerdict::Culled),
                                           v(ObjectVerdict::DrawnVisible)};
    const RasterCanvas canvas = overlaid(verdicts, {});
    EXPECT_GT(pixelsOf(canvas, kMissedColour), 20u);
    EXPECT_GT(pixelsOf(canvas, kDrawnHiddenColour), 20u);
    EXPECT_GT(pixelsOf(canvas, kCulledColour), 20u);
    // Object 3, drawn and seen, at x = 6 m: its part of the canvas stays background.
    for (int y = 0; y < static_cast<int>(kOverlaySize); ++y) {
        for (int x = 48; x < static_cast<int>(kOverlaySize); ++x)
            EXPECT_EQ(canvas.at(x, y), kBackground) << x << "," << y;
    }
    // Nothing missed: no red at all.
    const std::vector<uint8_t> none = {v(ObjectVerdict::DrawnVisible), v(ObjectVerdict::Culled),
                                       v(ObjectVerdict::Culled), v(ObjectVerdict::Culled)};
    EXPECT_EQ(pixelsOf(overlaid(none, {}), kMissedColour), 0u);
}

TEST(ValidationOverlay, AMissedObjectsOwnPixelsAreTintedWhereGroundTruthShowsThem) {
    // Ground truth shows object 0 (ID 1) in a 4 x 4 block at the bottom left of the canvas (rows
    // bottom-up, as the renderer reads them), and object 3 (ID 4) beside it.
    std::vector<uint32_t> ids(size_t{kOverlaySize} * kOverlaySize, 0);
    for (uint32_t y = 0; y < 4; ++y) {
        for (uint32_t x = 0; x < 4; ++x) {
            ids[size_t{y} * kOverlaySize + x] = 1;
            ids[size_t{y} * kOverlaySize + x + 8] = 4;
        }
    }
    const auto v = [](ObjectVerdict verdict) { return static_cast<uint8_t>(verdict); };
    const std::vector<uint8_t> verdicts = {v(ObjectVerdict::Missed), v(ObjectVerdict::Culled),
                                           v(ObjectVerdict::Culled),
                                           v(ObjectVerdict::DrawnVisible)};
    const RasterCanvas canvas = overlaid(verdicts, ids);
    const int bottom = static_cast<int>(kOverlaySize) - 1;  // canvas rows go down
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) {
            const Rgb tinted = canvas.at(x, bottom - y);
            EXPECT_GT(tinted.r, 120) << x << "," << y;
            EXPECT_LT(tinted.g, 60) << x << "," << y;
            EXPECT_EQ(canvas.at(x + 8, bottom - y), kBackground) << "drawn and seen: untouched";
        }
    }
    // An ID beyond the objects given is no object: left alone, no crash.
    ids[0] = 99;
    EXPECT_EQ(overlaid(verdicts, ids).at(0, bottom), kBackground);
}

TEST(ValidationOverlay, TheLegendListsCulledThenDrawnWhileHiddenThenMissedOnTop) {
    const auto classes = validationClasses();
    ASSERT_EQ(classes.size(), 3u);
    EXPECT_EQ(classes[0].verdict, ObjectVerdict::Culled);
    EXPECT_EQ(classes[1].verdict, ObjectVerdict::DrawnHidden);
    EXPECT_EQ(classes[2].verdict, ObjectVerdict::Missed);
    EXPECT_EQ(classes[2].colour, kMissedColour);
}

}  // namespace
}  // namespace occsim
