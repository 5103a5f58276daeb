// An OpenGL 4.5 core context that is current on the calling thread, with the entry points of
// gl_api.h loaded. Headless contexts come from a backend (render/headless_context.h: EGL, the
// default, or OSMesa where the build has it); a GLFW window context implements the same
// interface for the viewer.
#pragma once

#include <string>

namespace occsim {

class GlContext {
  public:
    virtual ~GlContext() = default;
    virtual std::string rendererName() const = 0;
};

}  // namespace occsim
