// A light's shadow map (render/gl_shadow_map.h) on a real headless context, in both depth
// conventions: a cube seen from straight above writes its top's depth where it covers the map
// and nothing elsewhere; the depth is the orthographic projection's for that distance; a map
// larger than the device's largest texture is refused.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <string>

#include "render/gl_api.h"
#include "render/gl_renderer.h"
#include "render/gl_shadow_map.h"
#include "render/headless_context.h"
#include "render_test_scene.h"

namespace occsim {
namespace {

class GlShadowMapTest : public ::testing::TestWithParam<DepthConvention> {
  protected:
    void SetUp() override {
        context_ = createHeadlessContext({Backend::Egl, {}}, 32, 32);
        renderer_ = std::make_unique<GlRenderer>(32, 32, GetParam());
        const MeshData cube = cubeMesh();
        renderer_->uploadMeshes(std::span<const MeshData>(&cube, 1));
        renderer_->setObjectMeshes(std::vector<uint32_t>{0});
    }
    std::unique_ptr<HeadlessContext> context_;
    std::unique_ptr<GlRenderer> renderer_;
};

TEST_P(GlShadowMapTest, ACasterWritesItsDepthWhereItCoversTheMapAndNothingElsewhere) {
    // The light 10 m above the origin looking straight down; its box 8 m across, 1 to 20 m deep.
    // The caster: a 2 m cube centred at the origin, its top 9 m below the light.
    const glm::dvec3 eye(0.0, 10.0, 0.0);
    ViewSetup light;
    light.eye = eye;
    light.box_origin = eye;
    light.view_rotation = glm::lookAt(glm::vec3(0), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1));
    light.projection = orthographicFor(GetParam(), -4, 4, -4, 4, 1, 20);
    // Model-view as the renderer takes it: the view's rotation after the eye-relative model.
    const std::vector<glm::mat4> model_view = {
        light.view_rotation * glm::mat4(glm::translate(glm::dmat4(1.0), glm::dvec3(0.0) - eye) *
                                        glm::scale(glm::dmat4(1.0), glm::dvec3(2.0)))};
    renderer_->setView(light, model_view);
    GlShadowMap map(64);
    map.begin(*renderer_);
    renderer_->drawObject(0);
    renderer_->finish();
    std::vector<float> depth;
    map.readDepth(depth);
    ASSERT_EQ(depth.size(), 64u * 64u);
    const bool reverse = GetParam() == DepthConvention::ReverseFloat;
    const float cleared = reverse ? 0.0f : 1.0f;
    // Depth 9 m between near 1 and far 20.
    const float expected = reverse ? (20.0f - 9.0f) / 19.0f : (9.0f - 1.0f) / 19.0f;
    uint32_t covered = 0;
    for (uint32_t y = 0; y < 64; ++y) {
        for (uint32_t x = 0; x < 64; ++x) {
            const float d = depth[y * 64 + x];
            // Texel centres at (x + 0.5) / 8 - 4 metres: the cube covers |.| < 1, 16 texels a side.
            const double wx = (x + 0.5) / 8.0 - 4.0, wy = (y + 0.5) / 8.0 - 4.0;
            if (std::abs(wx) < 1.0 && std::abs(wy) < 1.0) {
                ++covered;
                EXPECT_NEAR(d, expected, 1e-5) << x << "," << y;
            } else {
                EXPECT_EQ(d, cleared) << x << "," << y;
            }
        }
    }
    EXPECT_EQ(covered, 16u * 16u);
}

TEST_P(GlShadowMapTest, AMapLargerThanTheDevicesLargestTextureIsRefused) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    EXPECT_THROW(GlShadowMap(static_cast<uint32_t>(max_size) + 1), std::runtime_error);
    EXPECT_THROW(GlShadowMap(0), std::runtime_error);
}

INSTANTIATE_TEST_SUITE_P(Conventions, GlShadowMapTest, bothDepthConventions(), depthConventionName);

}  // namespace
}  // namespace occsim
