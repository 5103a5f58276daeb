// What a context offers against what occsim needs, and what a run records about it.
#include <algorithm>
#include <cctype>
#include <sstream>

#include "render/gl_api.h"
#include "render/headless_backends.h"

namespace occsim {
namespace {

std::string glString(GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "";
}

GlCapabilities currentCapabilities() {
    GlCapabilities c;
    glGetIntegerv(GL_MAJOR_VERSION, &c.major);
    glGetIntegerv(GL_MINOR_VERSION, &c.minor);
    GLint mask = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    c.core_profile = (mask & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto* e =
            reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
        if (e) c.extensions.emplace_back(e);
    }
    c.renderer = glString(GL_RENDERER);
    c.version = glString(GL_VERSION);
    // Errors of the queries above (an old context without GL_CONTEXT_PROFILE_MASK) are not ours
    // to report: the version check below names what was found.
    while (glGetError() != GL_NO_ERROR) {
    }
    return c;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char ch) { return std::tolower(ch); });
    return s;
}

}  // namespace

const std::vector<std::string>& requiredGlExtensions() {
    static const std::vector<std::string> required = {"GL_ARB_occlusion_query2",
                                                      "GL_ARB_timer_query"};
    return required;
}

std::string checkGlRequirements(const GlCapabilities& found) {
    const std::string what_found = "found OpenGL " + std::to_string(found.major) + "." +
                                   std::to_string(found.minor) +
                                   (found.core_profile ? " core" : "") + " (\"" + found.version +
                                   "\" on " + found.renderer + ")";
    if (found.major < 4 || (found.major == 4 && found.minor < 5) || !found.core_profile) {
        return "needs an OpenGL 4.5 core profile context, " + what_found;
    }
    std::string missing;
    for (const std::string& e : requiredGlExtensions()) {
        if (std::find(found.extensions.begin(), found.extensions.end(), e) ==
            found.extensions.end()) {
            missing += (missing.empty() ? "" : ", ") + e;
        }
    }
    if (!missing.empty()) return "needs the extension(s) " + missing + ", missing on " + what_found;
    return {};
}

std::string driverOfVersion(const std::string& gl_version) {
    std::istringstream words(gl_version);
    std::string word, driver;
    bool first = true;
    while (words >> word) {
        // The leading "4.5" or "4.5.0" and the profile words are the API's, not the driver's.
        const bool profile = word == "(Core" || word == "Profile)" || word == "(Compatibility";
        if ((first && std::isdigit(static_cast<unsigned char>(word[0]))) || profile) {
            first = false;
            continue;
        }
        first = false;
        driver += (driver.empty() ? "" : " ") + word;
    }
    return driver.empty() ? gl_version : driver;
}

bool isSoftwareRenderer(const std::string& gl_renderer) {
    const std::string r = lower(gl_renderer);
    for (const char* software : {"llvmpipe", "softpipe", "swiftshader", "software rasterizer"}) {
        if (r.find(software) != std::string::npos) return true;
    }
    return false;
}

ContextInfo checkedContextInfo(Backend backend, std::optional<uint32_t> device,
                               const std::string& where) {
    const GlCapabilities found = currentCapabilities();
    if (const std::string problem = checkGlRequirements(found); !problem.empty()) {
        throw BackendUnavailable(where + ": " + problem);
    }
    ContextInfo info;
    info.backend = backend;
    info.device = device;
    info.vendor = glString(GL_VENDOR);
    info.renderer = found.renderer;
    info.version = found.version;
    info.driver = driverOfVersion(found.version);
    info.gpu_time_meaningful = !isSoftwareRenderer(found.renderer);
    GLint max_texture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
    info.max_texture_size = static_cast<uint32_t>(std::max(max_texture, 0));
    return info;
}

std::string HeadlessContext::rendererName() const {
    return info_.renderer + ", OpenGL " + info_.version;
}

}  // namespace occsim
