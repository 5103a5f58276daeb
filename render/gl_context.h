// An OpenGL 4.5 core context that is current on the calling thread, with the entry points of
// gl_api.h loaded. OSMesa (headless, software: Mesa's llvmpipe) is the default; a GLFW window
// context implements the same interface for the viewer.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace occsim {

class GlContext {
public:
    virtual ~GlContext() = default;
    virtual std::string rendererName() const = 0;
};

// Creates a headless OSMesa core-profile context of at least GL 4.5 and makes it current.
// Throws std::runtime_error with a one-line reason when that is impossible.
std::unique_ptr<GlContext> createOsMesaContext(uint32_t width, uint32_t height);

}  // namespace occsim
