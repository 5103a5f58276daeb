#include "render/glfw_library.h"

#include <dlfcn.h>

#include <string>

#include "render/glfw_context.h"

namespace occsim {
namespace {

constexpr const char* kLibraryName = "libglfw.so.3";

GlfwLibrary load() {
    // Never dlclose'd: GLFW in turn loads libGL and the Mesa driver, which keep thread-local and
    // at-exit state; unloading them from a running process invites a crash at exit.
    void* handle = dlopen(kLibraryName, RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
        const char* why = dlerror();
        throw WindowUnavailable(std::string("cannot load ") + kLibraryName + " (" +
                                (why ? why : "unknown reason") +
                                "); install GLFW 3 (Debian: libglfw3)");
    }
    GlfwLibrary lib;
#define OCCSIM_GLFW_LOOKUP(name)                                                                 \
    lib.name = reinterpret_cast<decltype(lib.name)>(dlsym(handle, #name));                       \
    if (lib.name == nullptr) {                                                                   \
        throw WindowUnavailable(std::string(kLibraryName) + " has no " #name                     \
                                                            "; occsim needs GLFW 3.3 or newer"); \
    }
    OCCSIM_GLFW_FUNCTIONS(OCCSIM_GLFW_LOOKUP)
#undef OCCSIM_GLFW_LOOKUP
    return lib;
}

}  // namespace

const GlfwLibrary& glfwLibrary() {
    static const GlfwLibrary library = load();
    return library;
}

}  // namespace occsim
