#include "render/gl_checked_call.h"

#include <cstdio>
#include <cstdlib>

namespace occsim {
namespace {

const char* glErrorName(GLenum error) {
    switch (error) {
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        case GL_STACK_UNDERFLOW:
            return "GL_STACK_UNDERFLOW";
        case GL_STACK_OVERFLOW:
            return "GL_STACK_OVERFLOW";
        default:
            return "unknown GL error";
    }
}

}  // namespace

std::string glErrorAfter(const char* call) {
    const GLenum error = glGetError();
    if (error == GL_NO_ERROR) return {};
    char code[16];
    std::snprintf(code, sizeof code, "0x%x", static_cast<unsigned>(error));
    return std::string(call) + ": " + glErrorName(error) + " (" + code + ")";
}

void checkGlCall(const char* call) {
    const std::string error = glErrorAfter(call);
    if (error.empty()) return;
    std::fprintf(stderr, "occsim: GL error on the query path after %s\n", error.c_str());
    std::fflush(stderr);
    std::abort();
}

}  // namespace occsim
