// Choosing the headless backend: EGL unless asked otherwise, OSMesa when EGL is missing (and
// the build has it).
#include "render/headless_backends.h"

namespace occsim {

const char* backendName(Backend backend) {
    switch (backend) {
        case Backend::Auto:
            return "auto";
        case Backend::Egl:
            return "egl";
        case Backend::OsMesa:
            return "osmesa";
    }
    return "?";
}

std::optional<Backend> parseBackend(std::string_view name) {
    for (Backend b : {Backend::Auto, Backend::Egl, Backend::OsMesa}) {
        if (name == backendName(b)) return b;
    }
    return std::nullopt;
}

bool osmesaAvailable() {
#ifdef OCCSIM_HAVE_OSMESA
    return true;
#else
    return false;
#endif
}

#ifndef OCCSIM_HAVE_OSMESA
std::unique_ptr<HeadlessContext> createOsMesaContext(uint32_t, uint32_t) {
    throw BackendUnavailable(
        "--backend osmesa: this build has no OSMesa (configured with OCCSIM_WITH_OSMESA=OFF or "
        "without libosmesa6-dev); use --backend egl");
}
#endif

std::unique_ptr<HeadlessContext> createHeadlessContext(const BackendChoice& choice, uint32_t width,
                                                       uint32_t height) {
    if (choice.device && choice.backend == Backend::OsMesa) {
        throw BackendUnavailable("--device " + std::to_string(*choice.device) +
                                 ": only the EGL backend has devices, got --backend osmesa");
    }
    switch (choice.backend) {
        case Backend::Egl:
            try {
                return createEglContext(choice.device);
            } catch (const EglMissing& missing) {
                throw BackendUnavailable(std::string("--backend egl: ") + missing.what());
            }
        case Backend::OsMesa:
            return createOsMesaContext(width, height);
        case Backend::Auto:
            try {
                return createEglContext(choice.device);
            } catch (const EglMissing& missing) {
                // A device was asked for: only EGL has devices, so there is nothing to fall back
                // on.
                if (choice.device || !osmesaAvailable()) {
                    throw BackendUnavailable(
                        std::string("no headless backend: ") + missing.what() +
                        (osmesaAvailable() ? "" : ", and this build has no OSMesa"));
                }
                auto context = createOsMesaContext(width, height);
                context->noteFallback(missing.what());
                return context;
            }
    }
    throw BackendUnavailable("unknown backend");
}

}  // namespace occsim
