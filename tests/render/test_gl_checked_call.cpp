// A GL error on the query path is reported with the name of the call that raised it.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "render/gl_checked_call.h"
#include "render_test_scene.h"

namespace occsim {
namespace {

// The debug builds' checked calls on the query path report a GL error with the call's text.
TEST_P(RenderTest, AGlErrorOnTheQueryPathIsReportedWithTheCallsName) {
    EXPECT_EQ(glErrorAfter("glFlush()"), "") << "no error pending";
    glEndQuery(GL_SAMPLES_PASSED);  // no query begun: GL_INVALID_OPERATION
    EXPECT_EQ(glErrorAfter("glEndQuery(GL_SAMPLES_PASSED)"),
              "glEndQuery(GL_SAMPLES_PASSED): GL_INVALID_OPERATION (0x502)");
    EXPECT_EQ(glErrorAfter("glFlush()"), "") << "the reported error is cleared";
}

}  // namespace
}  // namespace occsim
