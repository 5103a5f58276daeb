// What a context must offer: OpenGL 4.5 core and the extensions, each missing one named.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render/headless_context.h"

namespace occsim {
namespace {

GlCapabilities enough() {
    GlCapabilities c;
    c.major = 4;
    c.minor = 5;
    c.core_profile = true;
    c.extensions = requiredGlExtensions();
    c.renderer = "Some GPU";
    c.version = "4.5.0 Vendor 1.2";
    return c;
}

TEST(GlRequirements, A45CoreContextWithTheExtensionsIsEnough) {
    EXPECT_EQ(checkGlRequirements(enough()), "");
    GlCapabilities newer = enough();
    newer.minor = 6;
    EXPECT_EQ(checkGlRequirements(newer), "");
}

TEST(GlRequirements, BelowFourFiveNamesTheVersionFound) {
    GlCapabilities old = enough();
    old.minor = 3;
    old.version = "4.3 (Core Profile) Mesa 20.0";
    const std::string problem = checkGlRequirements(old);
    EXPECT_NE(problem.find("needs an OpenGL 4.5 core"), std::string::npos) << problem;
    EXPECT_NE(problem.find("found OpenGL 4.3 core"), std::string::npos) << problem;
    EXPECT_NE(problem.find("Some GPU"), std::string::npos) << problem;
    GlCapabilities compatibility = enough();
    compatibility.core_profile = false;
    EXPECT_NE(checkGlRequirements(compatibility).find("found OpenGL 4.5 ("), std::string::npos);
}

TEST(GlRequirements, AMissingExtensionIsNamed) {
    GlCapabilities c = enough();
    c.extensions = {"GL_ARB_occlusion_query2"};
    const std::string problem = checkGlRequirements(c);
    EXPECT_NE(problem.find("GL_ARB_timer_query"), std::string::npos) << problem;
    EXPECT_EQ(problem.find("GL_ARB_occlusion_query2,"), std::string::npos) << problem;
}

TEST(GlRequirements, TheDriverIsTheVersionStringWithoutTheApiVersion) {
    EXPECT_EQ(driverOfVersion("4.5 (Core Profile) Mesa 22.3.6"), "Mesa 22.3.6");
    EXPECT_EQ(driverOfVersion("4.6.0 NVIDIA 535.54.03"), "NVIDIA 535.54.03");
    EXPECT_EQ(driverOfVersion("4.6 (Core Profile) Mesa 23.2.1 (LLVM 15.0.7)"),
              "Mesa 23.2.1 (LLVM 15.0.7)");
    EXPECT_EQ(driverOfVersion("4.5"), "4.5");
}

TEST(GlRequirements, SoftwareRenderersAreRecognised) {
    EXPECT_TRUE(isSoftwareRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
    EXPECT_TRUE(isSoftwareRenderer("softpipe"));
    EXPECT_TRUE(isSoftwareRenderer("Google SwiftShader"));
    EXPECT_FALSE(isSoftwareRenderer("NVIDIA GeForce RTX 3080/PCIe/SSE2"));
    EXPECT_FALSE(
        isSoftwareRenderer("AMD Radeon RX 6800 (radeonsi, navi21, LLVM 15.0.6, DRM 3.49)"));
}

}  // namespace
}  // namespace occsim
