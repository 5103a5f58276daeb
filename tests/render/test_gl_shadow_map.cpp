// A light's shadow map (render/gl_shadow_map.h) on a real headless context, in both depth
// conventions: a cube seen from straight above writes its top's depth where it covers the map
// and nothing elsewhere; the depth is the orthographic projection's for that distance; a map
// larger than the device's largest texture is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// A camera pass with the shadow term (GlRenderer::setShadow): a ground slab (object 0, top at
// y = 0) and a unit cube (object 1) centred 3 m above it, the light travelling along
// (1, -1, 0) / sqrt(2), so the cube's shadow on the ground is x in [2, 4], z in [-0.5, 0.5]; the
// camera 10 m above (3, 0, 0) looking straight down. Every ground pixel well inside that shadow
// is shadowed by a texel whose caster is the cube, every ground pixel well outside it is lit,
// and so is the cube's top; the same 10^6 m from the origin.
class GlShadowTermTest : public ::testing::TestWithParam<DepthConvention> {
  protected:
    static constexpr uint32_t kSide = 128, kMap = 256;
    void SetUp() override {
        context_ = createHeadlessContext({Backend::Egl, {}}, kSide, kSide);
        renderer_ = std::make_unique<GlRenderer>(kSide, kSide, GetParam());
        const MeshData cube = cubeMesh();
        renderer_->uploadMeshes(std::span<const MeshData>(&cube, 1));
        renderer_->setObjectMeshes(std::vector<uint32_t>{0, 0});
    }
    // Object model-view matrices for a view, relative to its eye in double.
    std::vector<glm::mat4> modelViews(const ViewSetup& view, const glm::dvec3& origin) const {
        const glm::dmat4 ground = glm::translate(glm::dmat4(1.0), origin + glm::dvec3(0, -0.1, 0)) *
                                  glm::scale(glm::dmat4(1.0), glm::dvec3(40.0, 0.2, 40.0));
        const glm::dmat4 caster = glm::translate(glm::dmat4(1.0), origin + glm::dvec3(0, 3, 0));
        std::vector<glm::mat4> out;
        for (const glm::dmat4& world : {ground, caster}) {
            out.push_back(view.view_rotation *
                          glm::mat4(glm::translate(glm::dmat4(1.0), -view.eye) * world));
        }
        return out;
    }
    // Both objects drawn into `map` from `light`; how `camera` looks it up.
    ShadowLookup renderMap(GlShadowMap& map, const ViewSetup& light, const ViewSetup& camera,
                           const glm::dvec3& origin) {
        renderer_->setView(light, modelViews(light, origin));
        map.begin(*renderer_);
        renderer_->drawObject(0);
        renderer_->drawObject(1);
        return map.lookupFor(camera, light, GetParam());
    }
    std::unique_ptr<HeadlessContext> context_;
    std::unique_ptr<GlRenderer> renderer_;
};

TEST_P(GlShadowTermTest, TheGroundUnderACastersShadowIsShadowedByItAndTheRestIsLit) {
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, 0.0, -1e6)}) {
        SCOPED_TRACE(origin.x);
        const glm::dvec3 travel = glm::normalize(glm::dvec3(1, -1, 0));
        ViewSetup light;
        light.eye = origin + glm::dvec3(3, 0, 0) - 15.0 * travel;
        light.view_rotation = glm::mat4(glm::lookAt(glm::dvec3(0.0), travel, glm::dvec3(0, 1, 0)));
        light.projection = orthographicFor(GetParam(), -8, 8, -8, 8, 1, 40);
        ViewSetup camera;
        camera.eye = origin + glm::dvec3(3, 10, 0);
        camera.view_rotation =
            glm::mat4(glm::lookAt(glm::dvec3(0.0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, -1)));
        camera.projection = perspectiveFor(GetParam(), glm::radians(90.0f), 1.0f, 0.5f, 100.0f);

        GlShadowMap map(kMap, /*caster_ids=*/true);
        const ShadowLookup lookup = renderMap(map, light, camera, origin);
        renderer_->setView(camera, modelViews(camera, origin));
        renderer_->setShadow(&lookup);
        renderer_->beginFrame();
        renderer_->drawObject(0);
        renderer_->drawObject(1);
        renderer_->finish();
        std::vector<uint32_t> ids, texels, casters;
        renderer_->readObjectIds(ids);
        renderer_->readShadowTexels(texels);
        map.readCasterIds(casters);

        uint32_t shadowed = 0, lit = 0, top = 0;
        for (uint32_t y = 0; y < kSide; ++y) {
            for (uint32_t x = 0; x < kSide; ++x) {
                const size_t i = size_t{y} * kSide + x;
                if (ids[i] == 2) {
                    // The cube's top (x in [-0.5, 0.5] 6.5 m down) faces the light; its +x side,
                    // seen beside the top, is in the cube's own shadow.
                    const double tx = 3.0 + ((x + 0.5) / (kSide / 2.0) - 1.0) * 6.5;
                    if (std::abs(tx) < 0.45) {
                        ++top;
                        EXPECT_EQ(texels[i], 0u) << x << "," << y;
                    }
                    continue;
                }
                ASSERT_EQ(ids[i], 1u) << x << "," << y;
                // The ground point at this pixel: the camera's right is +x, its up -z, 10 m down
                // with a 90 degree field of view.
                const double gx = 3.0 + ((x + 0.5) / (kSide / 2.0) - 1.0) * 10.0;
                const double gz = -((y + 0.5) / (kSide / 2.0) - 1.0) * 10.0;
                const bool inside = gx > 2.3 && gx < 3.7 && std::abs(gz) < 0.2;
                const bool outside = gx < 1.7 || gx > 4.3 || std::abs(gz) > 0.8;
                if (inside) {
                    ++shadowed;
                    ASSERT_NE(texels[i], 0u) << x << "," << y;
                    ASSERT_LE(texels[i], kMap * kMap);
                    EXPECT_EQ(casters[texels[i] - 1], 2u) << x << "," << y;
                } else if (outside) {
                    ++lit;
                    EXPECT_EQ(texels[i], 0u) << x << "," << y;
                }
            }
        }
        EXPECT_GT(shadowed, 10u);
        EXPECT_GT(lit, 1000u);
        EXPECT_GT(top, 4u);

        // Without the term, nothing is shadowed.
        renderer_->setShadow(nullptr);
        renderer_->beginFrame();
        renderer_->drawObject(0);
        renderer_->drawObject(1);
        renderer_->readShadowTexels(texels);
        EXPECT_EQ(std::count(texels.begin(), texels.end(), 0u), std::ptrdiff_t{kSide * kSide});
    }
}

// A shading pass after a depth pass (GlRenderer::redrawObject): the frame drawn unshaded, then
// every object drawn again with the shadow term over its own depth, gives the IDs, colours and
// shadow texels of the frame drawn shaded in one pass.
TEST_P(GlShadowTermTest, ARedrawShadesExactlyWhatOnePassWouldHave) {
    const glm::dvec3 origin(0.0);
    const glm::dvec3 travel = glm::normalize(glm::dvec3(1, -1, 0.3));
    ViewSetup light;
    light.eye = origin + glm::dvec3(3, 0, 0) - 15.0 * travel;
    light.view_rotation = glm::mat4(glm::lookAt(glm::dvec3(0.0), travel, glm::dvec3(0, 1, 0)));
    light.projection = orthographicFor(GetParam(), -8, 8, -8, 8, 1, 40);
    ViewSetup camera;
    camera.eye = origin + glm::dvec3(-2, 6, 9);
    camera.view_rotation = glm::mat4(
        glm::lookAt(glm::dvec3(0.0), glm::normalize(glm::dvec3(5, -6, -9)), glm::dvec3(0, 1, 0)));
    camera.projection = perspectiveFor(GetParam(), glm::radians(60.0f), 1.0f, 0.5f, 100.0f);
    GlShadowMap map(kMap);
    const ShadowLookup lookup = renderMap(map, light, camera, origin);
    renderer_->setView(camera, modelViews(camera, origin));

    // What the frame holds: IDs, shadow texels, colour.
    struct Frame {
        std::vector<uint32_t> ids, texels;
        std::vector<uint8_t> colour;
    };
    auto read = [this] {
        Frame f;
        renderer_->readObjectIds(f.ids);
        renderer_->readShadowTexels(f.texels);
        renderer_->readColor(f.colour);
        return f;
    };
    renderer_->setShadow(&lookup);
    renderer_->beginFrame();
    renderer_->drawObject(0);
    renderer_->drawObject(1);
    const Frame one_pass = read();

    renderer_->setShadow(nullptr);
    renderer_->beginFrame();
    renderer_->drawObject(1);  // another order: the depth test decides, not the order
    renderer_->drawObject(0);
    renderer_->setShadow(&lookup);
    renderer_->resumeFrame();
    renderer_->redrawObject(0);
    renderer_->redrawObject(1);
    const Frame two_passes = read();
    EXPECT_EQ(two_passes.ids, one_pass.ids);
    EXPECT_EQ(two_passes.texels, one_pass.texels);
    EXPECT_EQ(two_passes.colour, one_pass.colour);
    EXPECT_GT(std::count_if(one_pass.texels.begin(), one_pass.texels.end(),
                            [](uint32_t t) { return t != 0; }),
              50)
        << "the cube's shadow is in view";
}

INSTANTIATE_TEST_SUITE_P(Conventions, GlShadowTermTest, bothDepthConventions(),
                         depthConventionName);

TEST_P(GlShadowMapTest, AMapLargerThanTheDevicesLargestTextureIsRefused) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    EXPECT_THROW(GlShadowMap(static_cast<uint32_t>(max_size) + 1), std::runtime_error);
    EXPECT_THROW(GlShadowMap(0), std::runtime_error);
}

INSTANTIATE_TEST_SUITE_P(Conventions, GlShadowMapTest, bothDepthConventions(), depthConventionName);

}  // namespace
}  // namespace occsim
