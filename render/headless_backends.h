// The backends behind createHeadlessContext() (render/headless_context.h), for its own use.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "render/headless_context.h"

namespace occsim {

// EGL itself is not there (no libEGL, no device enumeration, no device at all): the one case in
// which Backend::Auto falls back to OSMesa.
struct EglMissing : BackendUnavailable {
    using BackendUnavailable::BackendUnavailable;
};

std::unique_ptr<HeadlessContext> createEglContext(std::optional<uint32_t> device);
// Only in builds with OSMesa (osmesaAvailable()).
std::unique_ptr<HeadlessContext> createOsMesaContext(uint32_t width, uint32_t height);

// With the new context current and its entry points loaded: reads what it offers, throws
// BackendUnavailable (prefixed with `where`, e.g. "egl device 0") when it is not enough, and
// returns what a run records about it.
ContextInfo checkedContextInfo(Backend backend, std::optional<uint32_t> device,
                               const std::string& where);

}  // namespace occsim
