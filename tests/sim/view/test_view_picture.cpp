// The viewer's picture (sim/view/view_picture.h) with the validation overlay
// (sim/output/validation_overlay.h) on a real frame: missed objects, objects drawn while hidden
// and culled ones, each in its colour, from the same comparison as the run's counts. Headless, on
// every backend the build has. The node boxes: test_node_boxes.cpp.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "sim/output/validation_overlay.h"
#include "sim/view/view_picture.h"
#include "view_gl_fixture.h"

namespace occsim {
namespace {

// A culler that draws nothing: everything ground truth sees is missed.
class DrawsNothing final : public Culler {
  public:
    void reset(const BspTree&) override {}
    void cullAndRender(const BspTree&, const CullFrame&, RenderDevice&) override {}
};

// The validation overlay shows each object's verdict against ground truth, from the same
// comparison as the run's counts: VFC over-draws (yellow boxes) and misses nothing; a culler that
// draws nothing misses what ground truth sees (its pixels tinted red) and over-draws nothing.
TEST_P(ViewGl, TheValidationOverlayShowsMissedDrawnHiddenAndCulledObjects) {
    ViewLayers layers;
    layers.hud = false;
    std::vector<uint8_t> rgba;
    auto verdicts = [](const Simulation& sim, ObjectVerdict v) {
        const auto& all = sim.objectVerdicts();
        return static_cast<int64_t>(std::count(all.begin(), all.end(), static_cast<uint8_t>(v)));
    };
    auto vfc = simulation("vfc", true);
    const FrameStats stats = vfc->renderFrame();
    ASSERT_EQ(vfc->objectVerdicts().size(), scene_->objectCount());
    EXPECT_EQ(verdicts(*vfc, ObjectVerdict::Missed), stats.missed_objects);
    EXPECT_EQ(verdicts(*vfc, ObjectVerdict::DrawnHidden), stats.overdrawn_objects);
    EXPECT_EQ(verdicts(*vfc, ObjectVerdict::DrawnVisible),
              stats.visible_objects - stats.missed_objects);
    EXPECT_GT(stats.overdrawn_objects, 0);
    renderer_->readColor(rgba);
    const RasterCanvas plain = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  *vfc, scenario_.camera, layers, {});
    layers.validation = true;
    const RasterCanvas shown = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  *vfc, scenario_.camera, layers, {});
    EXPECT_GT(countColour(shown, kDrawnHiddenColour), countColour(plain, kDrawnHiddenColour) + 100);
    EXPECT_EQ(countColour(shown, kMissedColour), countColour(plain, kMissedColour));

    const CullerRow& vfc_traits = *findCuller("vfc");
    SimulationOptions options;
    options.measure_error = true;
    Simulation nothing(*scene_, scenario_, vfc_traits, std::make_unique<DrawsNothing>(),
                       scenario_.culler, *renderer_, options);
    const FrameStats none = nothing.renderFrame();
    EXPECT_EQ(verdicts(nothing, ObjectVerdict::Missed), none.visible_objects);
    EXPECT_EQ(verdicts(nothing, ObjectVerdict::DrawnHidden), 0);
    renderer_->readColor(rgba);  // the empty culled frame, before ground truth draws over it
    GroundTruth truth(*renderer_);
    const std::vector<uint32_t> truth_ids = truth.of(nothing.world()).ids;
    layers.truth_ids = truth_ids;
    const RasterCanvas holes = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  nothing, scenario_.camera, layers, {});
    size_t reddish = 0;  // the missed objects' pixels, tinted red over the empty frame
    for (uint32_t y = 0; y < holes.height(); ++y) {
        for (uint32_t x = 0; x < holes.width(); ++x) {
            const Rgb c = holes.at(static_cast<int>(x), static_cast<int>(y));
            reddish += c.r > 120 && c.g < 60 && c.b < 60;
        }
    }
    size_t seen = 0;
    for (uint32_t id : truth_ids) seen += id != 0;
    EXPECT_GE(reddish, seen / 2) << "the missed objects' pixels, " << seen << " of them";
    EXPECT_GT(countColour(holes, kMissedColour), 100u) << "their boxes";
    EXPECT_GT(countColour(holes, kCulledColour), 100u) << "the hidden ones' boxes, grey";
}

}  // namespace
}  // namespace occsim
