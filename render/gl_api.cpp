#include "render/gl_api.h"

#include <cstdio>
#include <stdexcept>

#define OCCSIM_GL_DEFINE(type, name) type occsim_##name = nullptr;
extern "C" {
OCCSIM_GL_FUNCTIONS(OCCSIM_GL_DEFINE)
}
#undef OCCSIM_GL_DEFINE

namespace occsim {

bool loadGlFunctions(const GlProcLoader& loader, std::string* error) {
#define OCCSIM_GL_LOAD(type, name)                                        \
    occsim_##name = reinterpret_cast<type>(loader(#name));                \
    if (occsim_##name == nullptr) {                                       \
        if (error) *error = "OpenGL function " #name " is not available"; \
        return false;                                                     \
    }
    OCCSIM_GL_FUNCTIONS(OCCSIM_GL_LOAD)
#undef OCCSIM_GL_LOAD
    return true;
}

std::string glRendererDescription() {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    return std::string(renderer ? renderer : "unknown renderer") + ", OpenGL " +
           (version ? version : "unknown version");
}

void checkGl(const char* what) {
    GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        char buf[64];
        std::snprintf(buf, sizeof buf, " failed with GL error 0x%04x", err);
        throw std::runtime_error(std::string(what) + buf);
    }
}

}  // namespace occsim
