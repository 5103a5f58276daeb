// The frame timer's result after glFinish.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "render/gl_frame_timer.h"
#include "render_test_scene.h"

namespace occsim {
namespace {

// The timer query brackets a frame and its result is there after glFinish. Its value is only
// checked to be a number: on llvmpipe it does not time rasterisation.
TEST_P(RenderTest, TheFrameTimerGivesAResultAfterFinish) {
    GlFrameTimer timer;
    for (int frame = 0; frame < 2; ++frame) {
        timer.begin();
        renderer_->beginFrame();
        renderer_->drawObject(0);
        timer.end();
        renderer_->finish();
        const double ms = timer.resultMs();
        EXPECT_GE(ms, 0.0);
        EXPECT_TRUE(std::isfinite(ms));
    }
}

}  // namespace
}  // namespace occsim
