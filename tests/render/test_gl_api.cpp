// The GL entry points (render/gl_api.h): loaded through the context's loader, a missing one named;
// a GL error after a set-up call thrown with the call's name and the code; the context described.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "render/gl_api.h"
#include "render_test_scene.h"

namespace occsim {
namespace {

// A loader that has nothing: loading stops at the first entry point (glGetString) and names it.
// That one pointer is put back, so that the context stays usable for the test's own checks.
TEST_P(RenderTest, ALoaderWithoutAnEntryPointIsRefusedNamingIt) {
    const auto kept = occsim_glGetString;
    std::string error;
    EXPECT_FALSE(loadGlFunctions([](const char*) -> void* { return nullptr; }, &error));
    occsim_glGetString = kept;
    EXPECT_EQ(error, "OpenGL function glGetString is not available");
    EXPECT_NE(glRendererDescription().find(", OpenGL 4.5"), std::string::npos);
}

TEST_P(RenderTest, AGlErrorAfterACallIsThrownWithTheCallsNameAndTheCode) {
    EXPECT_NO_THROW(checkGl("nothing yet"));
    glEnable(0x1234);  // no such capability: GL_INVALID_ENUM
    try {
        checkGl("glEnable(0x1234)");
        ADD_FAILURE() << "an invalid enum passed unseen";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "glEnable(0x1234) failed with GL error 0x0500");
    }
    // glGetError cleared the flag: the next check is clean.
    EXPECT_NO_THROW(checkGl("after"));
}

TEST_P(RenderTest, TheDescriptionIsTheRendererAndTheVersion) {
    const std::string description = glRendererDescription();
    EXPECT_EQ(description.rfind(context_->info().renderer, 0), 0u) << description;
    EXPECT_NE(description.find(", OpenGL 4.5"), std::string::npos) << description;
}

}  // namespace
}  // namespace occsim
