// Headless GL through OSMesa (Mesa's llvmpipe), only in builds configured with it
// (OCCSIM_WITH_OSMESA; Mesa removed OSMesa in 25.1). OSMesa needs a client buffer to make a
// context current; occsim renders into its own framebuffer object, so that buffer only exists
// to satisfy the API. Mesa keeps a pointer to it beyond the context's life and copies frames
// into it: it comes from osmesaColourBuffer(), which never frees it (osmesa_colour_buffer.h says
// why), and the context is unbound before it is destroyed. There is no resize: a context keeps
// the size it was made with (the renderer resizes its framebuffer object instead); a resize would
// have to call OSMesaMakeCurrent with a buffer of the new size before rendering again.
#include <GL/osmesa.h>

#include <stdexcept>

#include "render/gl_loader.h"
#include "render/headless_backends.h"
#include "render/osmesa_colour_buffer.h"

namespace occsim {
namespace {

class OsMesaContext final : public HeadlessContext {
  public:
    OsMesaContext(uint32_t width, uint32_t height)
        : buffer_(osmesaColourBuffer(width, height)), width_(width), height_(height) {
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               0,
                               OSMESA_STENCIL_BITS,
                               0,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               5,
                               0};
        context_ = OSMesaCreateContextAttribs(attribs, nullptr);
        if (context_ == nullptr) {
            throw BackendUnavailable("OSMesa: cannot create an OpenGL 4.5 core context");
        }
        if (!OSMesaMakeCurrent(context_, buffer_, GL_UNSIGNED_BYTE, static_cast<GLsizei>(width),
                               static_cast<GLsizei>(height))) {
            OSMesaDestroyContext(context_);
            throw std::runtime_error("OSMesa: cannot make the context current");
        }
        std::string error;
        if (!loadGlFunctions(
                [](const char* name) {
                    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
                },
                &error)) {
            release();
            throw BackendUnavailable("OSMesa: " + error);
        }
    }
    ~OsMesaContext() override { release(); }
    OsMesaContext(const OsMesaContext&) = delete;
    OsMesaContext& operator=(const OsMesaContext&) = delete;

    void setInfo(ContextInfo info) { info_ = std::move(info); }

    void makeCurrent() override {
        if (!OSMesaMakeCurrent(context_, buffer_, GL_UNSIGNED_BYTE, static_cast<GLsizei>(width_),
                               static_cast<GLsizei>(height_))) {
            throw std::runtime_error("OSMesa: cannot make a context current again");
        }
    }

  private:
    // Unbound first, so that the flush that goes with unbinding happens while the context still
    // has its buffer; then destroyed.
    void release() {
        if (OSMesaGetCurrentContext() == context_) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
        OSMesaDestroyContext(context_);
    }

    unsigned char* buffer_;  // never freed: Mesa keeps it (osmesa_colour_buffer.h)
    uint32_t width_, height_;
    OSMesaContext context_ = nullptr;
};

}  // namespace

std::unique_ptr<HeadlessContext> createOsMesaContext(uint32_t width, uint32_t height) {
    auto context = std::make_unique<OsMesaContext>(width, height);
    context->setInfo(checkedContextInfo(Backend::OsMesa, std::nullopt, "OSMesa"));
    return context;
}

}  // namespace occsim
