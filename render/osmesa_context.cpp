// Headless GL through OSMesa (Mesa's llvmpipe), only in builds configured with it
// (OCCSIM_WITH_OSMESA; Mesa removed OSMesa in 25.1). OSMesa needs a client buffer to make a
// context current; occsim renders into its own framebuffer object, so that buffer only exists
// to satisfy the API.
#include <GL/osmesa.h>

#include <stdexcept>
#include <vector>

#include "render/gl_loader.h"
#include "render/headless_backends.h"

namespace occsim {
namespace {

class OsMesaContext final : public HeadlessContext {
  public:
    OsMesaContext(uint32_t width, uint32_t height) : buffer_(size_t{width} * height * 4) {
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
        if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE,
                               static_cast<GLsizei>(width), static_cast<GLsizei>(height))) {
            OSMesaDestroyContext(context_);
            throw std::runtime_error("OSMesa: cannot make the context current");
        }
        std::string error;
        if (!loadGlFunctions(
                [](const char* name) {
                    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
                },
                &error)) {
            OSMesaDestroyContext(context_);
            throw BackendUnavailable("OSMesa: " + error);
        }
    }
    ~OsMesaContext() override { OSMesaDestroyContext(context_); }
    OsMesaContext(const OsMesaContext&) = delete;
    OsMesaContext& operator=(const OsMesaContext&) = delete;

    void setInfo(ContextInfo info) { info_ = std::move(info); }

  private:
    std::vector<unsigned char> buffer_;
    OSMesaContext context_ = nullptr;
};

}  // namespace

std::unique_ptr<HeadlessContext> createOsMesaContext(uint32_t width, uint32_t height) {
    auto context = std::make_unique<OsMesaContext>(width, height);
    context->setInfo(checkedContextInfo(Backend::OsMesa, std::nullopt, "OSMesa"));
    return context;
}

}  // namespace occsim
