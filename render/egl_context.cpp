// Headless GL through EGL: devices from EGL_EXT_device_enumeration, a display per device from
// EGL_EXT_platform_device, an OpenGL 4.5 core context made current without any surface
// (EGL_KHR_surfaceless_context); occsim renders into its own framebuffer objects. libEGL is
// opened with dlopen, so an occsim binary starts (and falls back to OSMesa) where it is missing.
// The same code serves Mesa's software device and a GPU vendor's EGL driver (through glvnd).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>

#include "render/gl_loader.h"
#include "render/headless_backends.h"

namespace occsim {
namespace {

// The entry points occsim calls, from libEGL.so.1 (core) and eglGetProcAddress (extensions).
struct EglLibrary {
    PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
    PFNEGLQUERYSTRINGPROC queryString = nullptr;
    PFNEGLGETERRORPROC getError = nullptr;
    PFNEGLGETPLATFORMDISPLAYPROC getPlatformDisplay = nullptr;
    PFNEGLINITIALIZEPROC initialize = nullptr;
    PFNEGLBINDAPIPROC bindApi = nullptr;
    PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
    PFNEGLCREATECONTEXTPROC createContext = nullptr;
    PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
    PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
    PFNEGLGETCURRENTCONTEXTPROC getCurrentContext = nullptr;
    PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
    PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
    void* opengl = nullptr;  // libOpenGL.so.0, for GL functions eglGetProcAddress does not give
    std::string client_extensions;
    std::string problem;  // why EGL cannot be used; empty when it can
};

bool hasExtension(const std::string& list, const char* name) {
    std::istringstream words(list);
    std::string word;
    while (words >> word) {
        if (word == name) return true;
    }
    return false;
}

template <class F>
bool loadSymbol(void* library, const char* name, F& f) {
    f = reinterpret_cast<F>(dlsym(library, name));
    return f != nullptr;
}

EglLibrary loadEgl() {
    EglLibrary egl;
    // Never closed: EGL drivers do not expect to be unloaded while the process runs.
    void* library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        const char* why = dlerror();
        egl.problem = std::string("cannot load libEGL.so.1 (") + (why ? why : "not found") +
                      "); install libegl1 and an EGL driver (libegl-mesa0, or the GPU vendor's)";
        return egl;
    }
    const bool core = loadSymbol(library, "eglGetProcAddress", egl.getProcAddress) &&
                      loadSymbol(library, "eglQueryString", egl.queryString) &&
                      loadSymbol(library, "eglGetError", egl.getError) &&
                      loadSymbol(library, "eglInitialize", egl.initialize) &&
                      loadSymbol(library, "eglBindAPI", egl.bindApi) &&
                      loadSymbol(library, "eglChooseConfig", egl.chooseConfig) &&
                      loadSymbol(library, "eglCreateContext", egl.createContext) &&
                      loadSymbol(library, "eglDestroyContext", egl.destroyContext) &&
                      loadSymbol(library, "eglMakeCurrent", egl.makeCurrent) &&
                      loadSymbol(library, "eglGetCurrentContext", egl.getCurrentContext);
    if (!core || !loadSymbol(library, "eglGetPlatformDisplay", egl.getPlatformDisplay)) {
        egl.problem = "libEGL.so.1 lacks EGL 1.5 functions (eglGetPlatformDisplay); needs EGL 1.5";
        return egl;
    }
    const char* client = egl.queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    egl.client_extensions = client ? client : "";
    // EGL_EXT_device_base is the older name of enumeration and query together.
    const bool base = hasExtension(egl.client_extensions, "EGL_EXT_device_base");
    std::string missing;
    for (const char* e :
         {"EGL_EXT_device_enumeration", "EGL_EXT_device_query", "EGL_EXT_platform_device"}) {
        const bool in_base = std::strcmp(e, "EGL_EXT_platform_device") != 0 && base;
        if (!in_base && !hasExtension(egl.client_extensions, e)) {
            missing += (missing.empty() ? "" : ", ") + std::string(e);
        }
    }
    if (!missing.empty()) {
        egl.problem = "EGL lacks " + missing + " (client extensions: " +
                      (egl.client_extensions.empty() ? "none: glvnd found no EGL vendor library; "
                                                       "install libegl-mesa0 or the GPU vendor's"
                                                     : egl.client_extensions) +
                      ")";
        return egl;
    }
    egl.queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(egl.getProcAddress("eglQueryDevicesEXT"));
    egl.queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        egl.getProcAddress("eglQueryDeviceStringEXT"));
    if (!egl.queryDevices || !egl.queryDeviceString) {
        egl.problem = "EGL advertises device enumeration but has no eglQueryDevicesEXT";
        return egl;
    }
    egl.opengl = dlopen("libOpenGL.so.0", RTLD_NOW | RTLD_LOCAL);
    return egl;
}

// Loaded once per process; throws EglMissing when EGL cannot be used at all.
const EglLibrary& egl() {
    static const EglLibrary library = loadEgl();
    if (!library.problem.empty()) throw EglMissing("EGL: " + library.problem);
    return library;
}

std::string eglErrorText(const EglLibrary& e) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "EGL error 0x%04x", static_cast<unsigned>(e.getError()));
    return buf;
}

std::vector<EGLDeviceEXT> devices(const EglLibrary& e) {
    EGLint count = 0;
    if (!e.queryDevices(0, nullptr, &count) || count <= 0) return {};
    std::vector<EGLDeviceEXT> list(static_cast<size_t>(count));
    if (!e.queryDevices(count, list.data(), &count)) return {};
    list.resize(static_cast<size_t>(count));
    return list;
}

std::string deviceKind(const EglLibrary& e, EGLDeviceEXT device) {
    const char* ext = e.queryDeviceString(device, EGL_EXTENSIONS);
    const std::string extensions = ext ? ext : "";
    if (hasExtension(extensions, "EGL_MESA_device_software")) return "software";
    if (hasExtension(extensions, "EGL_EXT_device_drm_render_node")) {
        if (const char* node = e.queryDeviceString(device, EGL_DRM_RENDER_NODE_FILE_EXT))
            return node;
    }
    if (hasExtension(extensions, "EGL_EXT_device_drm")) {
        if (const char* file = e.queryDeviceString(device, EGL_DRM_DEVICE_FILE_EXT)) return file;
    }
    return "unknown";
}

// An initialised display per device, kept for the process's lifetime: EGL displays are not
// reference-counted, so terminating one would pull it from under any other context on it.
struct Display {
    EGLDisplay display = EGL_NO_DISPLAY;
    std::string vendor, extensions;
};

Display displayOf(const EglLibrary& e, EGLDeviceEXT device, const std::string& where) {
    static std::mutex mutex;
    static std::map<EGLDeviceEXT, Display> displays;
    const std::lock_guard<std::mutex> lock(mutex);
    if (auto it = displays.find(device); it != displays.end()) return it->second;

    EGLint major = 0, minor = 0;
    EGLDisplay display = e.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    bool ok = display != EGL_NO_DISPLAY && e.initialize(display, &major, &minor);
    // Older Mesa cannot make a display of its software device; its surfaceless platform renders
    // on the same llvmpipe.
    if (!ok && deviceKind(e, device) == "software" &&
        hasExtension(e.client_extensions, "EGL_MESA_platform_surfaceless")) {
        display = e.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        ok = display != EGL_NO_DISPLAY && e.initialize(display, &major, &minor);
    }
    if (!ok)
        throw BackendUnavailable(where + ": cannot initialise its EGL display (" + eglErrorText(e) +
                                 ")");
    if (major < 1 || (major == 1 && minor < 5)) {
        throw BackendUnavailable(where + ": needs EGL 1.5, found EGL " + std::to_string(major) +
                                 "." + std::to_string(minor));
    }
    Display d;
    d.display = display;
    const char* vendor = e.queryString(display, EGL_VENDOR);
    const char* extensions = e.queryString(display, EGL_EXTENSIONS);
    d.vendor = vendor ? vendor : "";
    d.extensions = extensions ? extensions : "";
    if (!hasExtension(d.extensions, "EGL_KHR_surfaceless_context")) {
        throw BackendUnavailable(where +
                                 ": its EGL display lacks EGL_KHR_surfaceless_context (a context "
                                 "current without a surface); found: " +
                                 d.extensions);
    }
    displays.emplace(device, d);
    return d;
}

class EglContext final : public HeadlessContext {
  public:
    EglContext(const EglLibrary& e, const Display& display, const std::string& where)
        : egl_(e), display_(display.display) {
        if (!e.bindApi(EGL_OPENGL_API)) {
            throw BackendUnavailable(where + ": EGL cannot bind the desktop OpenGL API (" +
                                     eglErrorText(e) + ")");
        }
        EGLConfig config = EGL_NO_CONFIG_KHR;
        if (!hasExtension(display.extensions, "EGL_KHR_no_config_context")) {
            const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
            EGLint found = 0;
            if (!e.chooseConfig(display_, wanted, &config, 1, &found) || found < 1) {
                throw BackendUnavailable(where + ": no EGL config renders desktop OpenGL");
            }
        }
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
        context_ = e.createContext(display_, config, EGL_NO_CONTEXT, attributes);
        if (context_ == EGL_NO_CONTEXT) {
            const std::string error = eglErrorText(e);
            throw BackendUnavailable(where + ": cannot create an OpenGL 4.5 core context (" +
                                     error + "), found " + bestContextOffered(config));
        }
        if (!e.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
            const std::string error = eglErrorText(e);
            e.destroyContext(display_, context_);
            throw BackendUnavailable(
                where + ": cannot make the context current without a surface (" + error + ")");
        }
        std::string error;
        const bool loaded = loadGlFunctions(
            [&e](const char* name) -> void* {
                if (auto f = e.getProcAddress(name)) return reinterpret_cast<void*>(f);
                return e.opengl ? dlsym(e.opengl, name) : nullptr;
            },
            &error);
        if (!loaded) {
            release();
            throw BackendUnavailable(where + ": " + error);
        }
    }
    ~EglContext() override { release(); }
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    void setInfo(ContextInfo info) { info_ = std::move(info); }

    void makeCurrent() override {
        if (!egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
            throw std::runtime_error("EGL: cannot make a context current again (" +
                                     eglErrorText(egl_) + ")");
        }
    }

  private:
    // What the device offers instead, for the message: a context of any version, asked for
    // without one, and its GL_VERSION and GL_RENDERER.
    std::string bestContextOffered(EGLConfig config) const {
        const EGLint any[] = {EGL_NONE};
        EGLContext probe = egl_.createContext(display_, config, EGL_NO_CONTEXT, any);
        if (probe == EGL_NO_CONTEXT) return "no desktop OpenGL context at all";
        std::string found = "an unknown version";
        if (egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, probe)) {
            using GetString = const unsigned char* (*)(unsigned);
            if (auto get = reinterpret_cast<GetString>(egl_.getProcAddress("glGetString"))) {
                const auto* version = reinterpret_cast<const char*>(get(0x1F02));   // GL_VERSION
                const auto* renderer = reinterpret_cast<const char*>(get(0x1F01));  // GL_RENDERER
                found = std::string("OpenGL \"") + (version ? version : "?") + "\" on " +
                        (renderer ? renderer : "?");
            }
            egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        }
        egl_.destroyContext(display_, probe);
        return found;
    }

    // Unbound only when current: another context of the process may be the current one.
    void release() {
        if (context_ == EGL_NO_CONTEXT) return;
        if (egl_.getCurrentContext() == context_)
            egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        egl_.destroyContext(display_, context_);
        context_ = EGL_NO_CONTEXT;
    }

    const EglLibrary& egl_;
    EGLDisplay display_;
    EGLContext context_ = EGL_NO_CONTEXT;
};

std::string deviceList(const EglLibrary& e, const std::vector<EGLDeviceEXT>& list) {
    std::string text;
    for (size_t i = 0; i < list.size(); ++i) {
        text += (i ? ", " : "") + std::to_string(i) + ": " + deviceKind(e, list[i]);
    }
    return text;
}

std::unique_ptr<EglContext> contextOn(const EglLibrary& e, EGLDeviceEXT device, uint32_t index,
                                      const std::string& where) {
    auto context = std::make_unique<EglContext>(e, displayOf(e, device, where), where);
    context->setInfo(checkedContextInfo(Backend::Egl, index, where));
    return context;
}

}  // namespace

std::unique_ptr<HeadlessContext> createEglContext(std::optional<uint32_t> device) {
    const EglLibrary& e = egl();
    const std::vector<EGLDeviceEXT> list = devices(e);
    if (list.empty()) throw EglMissing("EGL lists no device (no EGL driver installed?)");
    const uint32_t index = device.value_or(0);
    if (index >= list.size()) {
        throw BackendUnavailable("--device " + std::to_string(index) +
                                 ": out of range, EGL lists " + std::to_string(list.size()) +
                                 (list.size() == 1 ? " device" : " devices") + " (" +
                                 deviceList(e, list) + "; see occsim devices)");
    }
    return contextOn(e, list[index], index, "EGL device " + std::to_string(index));
}

std::vector<EglDeviceInfo> listEglDevices() {
    const EglLibrary& e = egl();
    std::vector<EglDeviceInfo> infos;
    const std::vector<EGLDeviceEXT> list = devices(e);
    for (uint32_t i = 0; i < list.size(); ++i) {
        EglDeviceInfo info;
        info.index = i;
        info.kind = deviceKind(e, list[i]);
        const std::string where = "EGL device " + std::to_string(i);
        try {
            info.egl_vendor = displayOf(e, list[i], where).vendor;
            info.context = contextOn(e, list[i], i, where)->info();
        } catch (const BackendUnavailable& problem) {
            info.problem = problem.what();
        }
        infos.push_back(std::move(info));
    }
    return infos;
}

}  // namespace occsim
