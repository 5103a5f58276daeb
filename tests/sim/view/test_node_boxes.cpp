// The node boxes of the viewer's picture (sim/view/node_boxes.h): drawn in the colours of what the
// culler did, and only for a traced frame. Headless, on every backend the build has.
#include <gtest/gtest.h>

#include <stdexcept>

#include "sim/view/node_boxes.h"
#include "sim/view/view_picture.h"
#include "view_gl_fixture.h"

namespace occsim {
namespace {

TEST_P(ViewGl, NodeBoxesShowInTheColoursOfWhatTheCullerDidOnlyForATracedFrame) {
    auto sim = simulation("chc");
    ViewLayers layers;
    layers.boxes = true;
    layers.hud = false;
    std::vector<uint8_t> rgba;
    const Rgb visible = nodeClassColour(NodeClass::DrawnAfterQuery);

    sim->renderFrame();  // not traced: nothing to draw boxes from
    renderer_->readColor(rgba);
    const RasterCanvas plain = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  *sim, scenario_.camera, layers, {});
    EXPECT_EQ(
        countColour(plain, visible),
        countColour(canvasFromBottomUp(rgba, renderer_->width(), renderer_->height()), visible));

    LiveControls controls;
    controls.trace_every_frame = true;
    sim->world().setLiveControls(controls);
    for (int f = 0; f < 3; ++f) sim->renderFrame();  // CHC settles into querying
    renderer_->readColor(rgba);
    const RasterCanvas boxed = composeViewPicture(rgba, renderer_->width(), renderer_->height(),
                                                  *sim, scenario_.camera, layers, {});
    EXPECT_GT(countColour(boxed, visible), 100u);
    EXPECT_GT(countColour(boxed, nodeClassColour(NodeClass::OcclusionCulled)), 20u);
}

}  // namespace
}  // namespace occsim
