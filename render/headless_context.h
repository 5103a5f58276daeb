// Headless OpenGL: which backend makes the context, which device it runs on, and what the run
// records about it. EGL (EGL 1.5, device enumeration, a 4.5 core context current without any
// surface) is the default and runs unchanged on Mesa's software device and on a GPU's EGL
// driver; OSMesa is the fallback where EGL is missing, and only in builds configured with it
// (OCCSIM_WITH_OSMESA).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "occsim/culling/contract/input_error.h"
#include "render/gl_context.h"

namespace occsim {

enum class Backend : uint8_t { Auto, Egl, OsMesa };

const char* backendName(Backend backend);                    // "auto", "egl", "osmesa"
std::optional<Backend> parseBackend(std::string_view name);  // nullopt for an unknown name
bool osmesaAvailable();  // this build was configured with OSMesa

// What the user asked for (--backend, --device).
struct BackendChoice {
    Backend backend = Backend::Auto;
    std::optional<uint32_t> device;  // an EGL device index (occsim devices); default 0
};

// The context a run rendered with, as summary.json, report.md and the console name it.
struct ContextInfo {
    Backend backend = Backend::Egl;         // the one that made it (never Auto)
    std::optional<uint32_t> device;         // the EGL device index
    std::string vendor, renderer, version;  // GL_VENDOR, GL_RENDERER, GL_VERSION
    std::string driver;                     // the driver part of GL_VERSION ("Mesa 22.3.6")
    // False on software rasterisers (llvmpipe, softpipe, SwiftShader): their GL_TIME_ELAPSED
    // does not time rasterisation, so a GPU time figure would mislead (docs/headless-gpu.md).
    bool gpu_time_meaningful = false;
    std::string fallback;           // why --backend auto fell back to OSMesa; empty when it did not
    uint32_t max_texture_size = 0;  // GL_MAX_TEXTURE_SIZE: the largest shadow map it can hold
};

// The requested backend or device cannot serve: missing, out of range, or its context falls
// short of what occsim needs. The message is one line naming what is missing and what was found;
// the command line reports it as bad input (exit 2).
struct BackendUnavailable : InputError {
    using InputError::InputError;
};

class HeadlessContext : public GlContext {
  public:
    const ContextInfo& info() const { return info_; }
    std::string rendererName() const override;
    // Makes this context the calling thread's current one again, after another context of the
    // process was (a run gives some cullers a context of their own: sim/run/runner.cpp). A context
    // is current when created; destroying one that is not current leaves the current one be.
    virtual void makeCurrent() = 0;
    void noteFallback(const std::string& why) { info_.fallback = why; }

  protected:
    ContextInfo info_;
};

// Creates a headless OpenGL 4.5 core context as `choice` asks, makes it current and loads the
// GL entry points. Auto takes EGL and falls back to OSMesa only when EGL is missing (no
// libEGL, no device enumeration, no device). Throws BackendUnavailable (see above), or
// std::runtime_error for a failure inside a backend that is there.
std::unique_ptr<HeadlessContext> createHeadlessContext(const BackendChoice& choice, uint32_t width,
                                                       uint32_t height);

// One EGL device as `occsim devices` lists it. The GL strings come from a context made on it;
// when that fails, `problem` says why and they stay empty.
struct EglDeviceInfo {
    uint32_t index = 0;
    std::string kind;        // "software" (EGL_MESA_device_software), a DRM node, or "unknown"
    std::string egl_vendor;  // EGL_VENDOR of its display
    ContextInfo context;
    std::string problem;
};

// Every EGL device; throws BackendUnavailable when EGL or device enumeration is missing.
std::vector<EglDeviceInfo> listEglDevices();

// The GL side of a context, as found: what checkGlRequirements() judges.
struct GlCapabilities {
    int major = 0, minor = 0;
    bool core_profile = false;
    std::vector<std::string> extensions;
    std::string renderer, version;
};

// The extensions the cullers and the timings need (occlusion queries that count samples, timer
// queries), beyond OpenGL 4.5 core.
const std::vector<std::string>& requiredGlExtensions();

// Empty when `found` is enough; otherwise one line naming what is missing and what was found.
std::string checkGlRequirements(const GlCapabilities& found);

// The driver part of a GL_VERSION string: "4.5 (Core Profile) Mesa 22.3.6" -> "Mesa 22.3.6",
// "4.5.0 NVIDIA 535.54.03" -> "NVIDIA 535.54.03"; the whole string when it has no such part.
std::string driverOfVersion(const std::string& gl_version);

// Whether a GL_RENDERER names a software rasteriser (its GPU time figures are not meaningful).
bool isSoftwareRenderer(const std::string& gl_renderer);

}  // namespace occsim
