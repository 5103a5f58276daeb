// PNG encoding of a rendered image.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render/png_writer.h"
#include "render_test_scene.h"

namespace occsim {
namespace {

TEST_P(RenderTest, PngEncodingProducesAValidPngSignature) {
    renderer_->beginFrame();
    renderer_->drawObject(0);
    std::vector<uint8_t> rgba;
    renderer_->readColor(rgba);
    const std::vector<uint8_t> png = encodePngBottomUp(rgba, kW, kH);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png[1], 'P');
    EXPECT_EQ(png[2], 'N');
    EXPECT_EQ(png[3], 'G');
}

}  // namespace
}  // namespace occsim
