// Headless contexts on every backend the build has (EGL, and OSMesa where configured): a 4.5 core
// context on the backend asked for, the same image on each, and one-line reasons when a backend or
// device cannot serve.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "render_test_scene.h"

namespace occsim {
namespace {

TEST_P(RenderTest, ContextIsOpenGl45CoreOnTheBackendAskedFor) {
    EXPECT_NE(context_->rendererName().find("4.5"), std::string::npos) << context_->rendererName();
    const ContextInfo& info = context_->info();
    EXPECT_EQ(info.backend, GetParam());
    EXPECT_EQ(info.device.has_value(), GetParam() == Backend::Egl);
    EXPECT_FALSE(info.vendor.empty());
    EXPECT_FALSE(info.renderer.empty());
    EXPECT_FALSE(info.driver.empty());
    EXPECT_TRUE(info.fallback.empty());
}
// The same frame on every backend: the same object IDs, pixel for pixel (both are Mesa's llvmpipe
// here; on a GPU the rasteriser differs and only the counts of deterministic runs must agree).
TEST(HeadlessBackends, EveryBackendRendersTheSameObjectIds) {
    std::vector<std::vector<uint32_t>> images;
    for (Backend backend : testing::testedBackends()) {
        auto context = createHeadlessContext({backend, {}}, 64, 48);
        GlRenderer renderer(64, 48);
        const MeshData cube = cubeMesh();
        renderer.uploadMeshes(std::span<const MeshData>(&cube, 1));
        renderer.setObjectMeshes(std::vector<uint32_t>{0});
        ViewSetup view;
        view.projection = reverseZPerspective(glm::radians(60.0f), 64.0f / 48.0f, 0.1f, 100.0f);
        const std::vector<glm::mat4> model_view = {
            glm::translate(glm::mat4(1.0f), {0.3f, 0.1f, -3.0f})};
        renderer.setView(view, model_view);
        renderer.beginFrame();
        renderer.drawObject(0);
        images.emplace_back();
        renderer.readObjectIds(images.back());
        EXPECT_GT(std::count(images.back().begin(), images.back().end(), 1u), 100);
    }
    for (size_t i = 1; i < images.size(); ++i) EXPECT_EQ(images[i], images[0]);
}

TEST(HeadlessBackends, AutoTakesEglWhereEglIsThere) {
    auto context = createHeadlessContext({Backend::Auto, {}}, 16, 16);
    EXPECT_EQ(context->info().backend, Backend::Egl);
    EXPECT_EQ(context->info().device, 0u);
}

TEST(HeadlessBackends, EglListsTheSoftwareDeviceWithItsStrings) {
    const std::vector<EglDeviceInfo> devices = listEglDevices();
    ASSERT_FALSE(devices.empty());
    bool llvmpipe = false;
    for (const EglDeviceInfo& d : devices) {
        EXPECT_TRUE(d.problem.empty()) << d.problem;
        llvmpipe |= d.context.renderer.find("llvmpipe") != std::string::npos;
        if (d.context.renderer.find("llvmpipe") != std::string::npos) {
            EXPECT_EQ(d.kind, "software");
            EXPECT_FALSE(d.context.gpu_time_meaningful);
        }
    }
    EXPECT_TRUE(llvmpipe);
}

// Asserts `make` throws BackendUnavailable whose one-line message contains every part.
template <class F>
void expectUnavailable(F&& make, std::initializer_list<const char*> parts) {
    try {
        make();
        ADD_FAILURE() << "no BackendUnavailable";
    } catch (const BackendUnavailable& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        for (const char* part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
    }
}

TEST(HeadlessBackends, ADeviceOutOfRangeNamesTheIndexAndWhatEglLists) {
    const auto count = static_cast<uint32_t>(listEglDevices().size());
    expectUnavailable(
        [&] {
            createHeadlessContext({Backend::Egl, count}, 16, 16);
        },
        {"--device", "out of range", "software"});
    expectUnavailable(
        [&] {
            createHeadlessContext({Backend::Auto, count + 5}, 16, 16);
        },
        {"--device", "out of range"});
}
TEST(HeadlessBackends, OsmesaHasNoDevices) {
    expectUnavailable(
        [] {
            createHeadlessContext({Backend::OsMesa, 0u}, 16, 16);
        },
        {"--device 0", "only the EGL backend"});
}

TEST(HeadlessBackends, OsmesaInABuildWithoutItSaysSo) {
    if (osmesaAvailable())
        GTEST_SKIP() << "this build has OSMesa (the no-osmesa preset checks this)";
    expectUnavailable(
        [] {
            createHeadlessContext({Backend::OsMesa, {}}, 16, 16);
        },
        {"--backend osmesa", "no OSMesa", "OCCSIM_WITH_OSMESA=OFF"});
}

TEST(HeadlessBackends, BackendNamesRoundTrip) {
    for (Backend b : {Backend::Auto, Backend::Egl, Backend::OsMesa})
        EXPECT_EQ(parseBackend(backendName(b)), b);
    EXPECT_FALSE(parseBackend("vulkan"));
    EXPECT_FALSE(parseBackend("EGL"));
}

}  // namespace
}  // namespace occsim
