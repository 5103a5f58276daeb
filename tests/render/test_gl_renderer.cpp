// The renderer through a real headless context, on every backend the build has: object IDs,
// nearer surfaces winning, reverse-Z depth ranks, the same image far from the origin.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_scene.h"

namespace occsim {
namespace {

TEST_P(RenderTest, ObjectIdBufferHoldsObjectIndexPlusOneAndZeroForBackground) {
    renderer_->beginFrame();
    renderer_->drawObject(0);
    renderer_->drawObject(2);
    renderer_->finish();
    std::vector<uint32_t> ids;
    renderer_->readObjectIds(ids);
    ASSERT_EQ(ids.size(), size_t{kW} * kH);
    EXPECT_EQ(ids[(kH / 2) * kW + kW / 2], 1u) << "the wall fills the centre";
    EXPECT_EQ(ids[0], 0u) << "a corner sees background";
    EXPECT_GT(std::count(ids.begin(), ids.end(), 3u), 0) << "the side cube is visible";
}

TEST_P(RenderTest, NearerObjectWinsWhateverTheDrawOrder) {
    // Reverse-Z with GL_GREATER: the wall (nearer) hides the cube behind it in either order.
    for (int order = 0; order < 2; ++order) {
        renderer_->beginFrame();
        renderer_->drawObject(order ? 0 : 1);
        renderer_->drawObject(order ? 1 : 0);
        std::vector<uint32_t> ids;
        renderer_->readObjectIds(ids);
        EXPECT_EQ(std::count(ids.begin(), ids.end(), 2u), 0) << "order " << order;
    }
}
TEST_P(RenderTest, CameraFarFromTheOriginRendersTheSameImage) {
    // Camera-relative rendering: the same scene shifted by 10^6 m renders identically.
    renderer_->beginFrame();
    renderer_->drawObject(0);
    renderer_->drawObject(2);
    std::vector<uint32_t> near_origin;
    renderer_->readObjectIds(near_origin);
    const glm::dvec3 shift(1e6, -2e6, 3e6);
    for (glm::dmat4& w : world_) w = glm::translate(glm::dmat4(1.0), shift) * w;
    setEye(shift);
    renderer_->beginFrame();
    renderer_->drawObject(0);
    renderer_->drawObject(2);
    std::vector<uint32_t> far_away;
    renderer_->readObjectIds(far_away);
    EXPECT_EQ(near_origin, far_away);
}

// The basis of the tie tolerance (docs/error.md): a drawn object stores the same depth at a pixel
// whatever else was drawn before it, so ground truth and a culled frame agree on it exactly.
TEST_P(RenderTest, ADrawnObjectStoresTheSameDepthWhateverElseIsDrawn) {
    renderer_->beginFrame();
    renderer_->drawObject(0);
    std::vector<uint32_t> alone, ids_alone;
    renderer_->readDepthRanks(alone);
    renderer_->readObjectIds(ids_alone);
    renderer_->beginFrame();
    renderer_->drawObject(2);
    renderer_->drawObject(1);
    renderer_->drawObject(0);
    std::vector<uint32_t> after_others, ids_after;
    renderer_->readDepthRanks(after_others);
    renderer_->readObjectIds(ids_after);
    size_t wall = 0;
    for (size_t i = 0; i < alone.size(); ++i) {
        if (ids_alone[i] != 1) continue;
        ++wall;
        ASSERT_EQ(ids_after[i], 1u) << i;
        EXPECT_EQ(alone[i], after_others[i]) << "pixel " << i;
    }
    EXPECT_GT(wall, 100u);
}

TEST_P(RenderTest, DepthRanksAreZeroForBackgroundAndLargerForNearerSurfaces) {
    renderer_->beginFrame();
    renderer_->drawObject(0);  // the wall at 5 m
    renderer_->drawObject(2);  // the cube at 20 m, off to the side
    std::vector<uint32_t> ranks, ids;
    renderer_->readDepthRanks(ranks);
    renderer_->readObjectIds(ids);
    uint32_t wall_min = UINT32_MAX, cube_max = 0;
    size_t background = 0;
    for (size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] == 0) {
            EXPECT_EQ(ranks[i], 0u);
            ++background;
        }
        if (ids[i] == 1) wall_min = std::min(wall_min, ranks[i]);
        if (ids[i] == 3) cube_max = std::max(cube_max, ranks[i]);
    }
    EXPECT_GT(background, 0u);
    ASSERT_GT(cube_max, 0u);
    EXPECT_GT(wall_min, cube_max);
}

TEST(RenderDepthFormats, ConventionalDepthRanksAreTheFixedPointStepsNearerLarger) {
    auto context = createHeadlessContext({Backend::Auto, {}}, 64, 48);
    GlRenderer renderer(64, 48, DepthConvention::Conventional24);
    const MeshData cube = cubeMesh();
    renderer.uploadMeshes(std::span<const MeshData>(&cube, 1));
    renderer.setObjectMeshes(std::vector<uint32_t>{0, 0});
    ViewSetup view;
    view.projection = perspectiveFor(DepthConvention::Conventional24, glm::radians(90.0f),
                                     64.0f / 48, 0.1f, 1000.0f);
    const std::vector<glm::mat4> model_view = {glm::translate(glm::mat4(1.0f), {-1, 0, -3}),
                                               glm::translate(glm::mat4(1.0f), {4, 0, -30}) *
                                                   glm::scale(glm::mat4(1.0f), glm::vec3(6.0f))};
    renderer.setView(view, model_view);
    renderer.beginFrame();
    renderer.drawObject(0);
    renderer.drawObject(1);
    std::vector<uint32_t> ranks, ids;
    renderer.readDepthRanks(ranks);
    renderer.readObjectIds(ids);
    uint32_t near_min = UINT32_MAX, far_max = 0;
    for (size_t i = 0; i < ids.size(); ++i) {
        EXPECT_LE(ranks[i], 0xFFFFFFu) << "a 24-bit step";
        if (ids[i] == 0) {
            EXPECT_EQ(ranks[i], 0u);
        }
        if (ids[i] == 1) near_min = std::min(near_min, ranks[i]);
        if (ids[i] == 2) far_max = std::max(far_max, ranks[i]);
    }
    ASSERT_GT(far_max, 0u) << "the far cube shows";
    ASSERT_LT(near_min, UINT32_MAX) << "the near cube shows";
    EXPECT_GT(near_min, far_max);
}
// Stereo: the midpoint 1.5 m to the right, eyes 3 m apart, at x = 0 and x = 3. Each half of the
// double-height framebuffer holds what that eye alone sees (to a few edge pixels: the two renders
// round their matrices differently); the cube behind the wall shows to the right eye only.
TEST_P(RenderTest, AStereoViewDrawsEachEyeIntoItsHalfAsThatEyeAlone) {
    auto drawAll = [&] {
        renderer_->beginFrame();
        for (uint32_t o = 0; o < 3; ++o) renderer_->drawObject(o);
        std::vector<uint32_t> ids;
        renderer_->readObjectIds(ids);
        return ids;
    };
    renderer_->resize(kW, 2 * kH);
    setEye({1.5, 0, 0}, 0.0f, 3.0);
    const std::vector<uint32_t> pair = drawAll();
    renderer_->resize(kW, kH);
    for (int eye = 0; eye < 2; ++eye) {
        setEye({eye == 0 ? 0.0 : 3.0, 0, 0});
        const std::vector<uint32_t> alone = drawAll();
        size_t differ = 0, hidden_cube = 0;
        for (uint32_t y = 0; y < kH; ++y) {
            for (uint32_t x = 0; x < kW; ++x) {
                const uint32_t id = pair[size_t{stereoEyeFirstRow(eye, 2 * kH) + y} * kW + x];
                differ += id != alone[size_t{y} * kW + x];
                hidden_cube += id == 2u;
            }
        }
        EXPECT_LE(differ, size_t{kW} * kH / 200) << "eye " << eye;
        if (eye == 0) {
            EXPECT_EQ(hidden_cube, 0u) << "the left eye looks at the wall's middle";
        } else {
            EXPECT_GT(hidden_cube, 0u) << "the right eye sees past the wall's edge";
        }
    }
}

// setEyes: draws go to the chosen eye's half alone.
TEST_P(RenderTest, AStereoViewDrawsOnlyIntoTheEyesItIsGiven) {
    renderer_->resize(kW, 2 * kH);
    setEye({1.5, 0, 0}, 0.0f, 3.0);
    for (const StereoEyes eyes : {StereoEyes::Left, StereoEyes::Right, StereoEyes::Both}) {
        renderer_->setEyes(eyes);
        renderer_->beginFrame();
        renderer_->drawObject(0);
        std::vector<uint32_t> ids;
        renderer_->readObjectIds(ids);
        const size_t left_first = size_t{stereoEyeFirstRow(0, 2 * kH)} * kW;
        size_t left = 0, right = 0;
        for (size_t i = 0; i < ids.size(); ++i) (i >= left_first ? left : right) += ids[i] != 0;
        EXPECT_EQ(left > 0, eyes != StereoEyes::Right);
        EXPECT_EQ(right > 0, eyes != StereoEyes::Left);
    }
    renderer_->setEyes(StereoEyes::Both);
}

INSTANTIATE_TEST_SUITE_P(Backends, RenderTest, ::testing::ValuesIn(testing::testedBackends()),
                         testing::backendTestName);

}  // namespace
}  // namespace occsim
