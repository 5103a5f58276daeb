#include "render/glfw_context.h"

#include "render/gl_loader.h"
#include "render/glfw_library.h"

namespace occsim {
namespace {

// The error GLFW reported last, for messages ("X11: The DISPLAY environment variable is missing").
std::string lastGlfwError(const GlfwLibrary& glfw) {
    const char* description = nullptr;
    glfw.glfwGetError(&description);
    return description ? description : "no reason given";
}

// GLFW key codes to the names of window_events.h; keys not listed are not reported.
std::string_view keyName(int key) {
    if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z)
        return keyNames()[static_cast<size_t>(key - GLFW_KEY_A)];
    if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) {
        return keyNames()[26 + static_cast<size_t>(key - GLFW_KEY_0)];
    }
    if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F12) {
        return keyNames()[36 + static_cast<size_t>(key - GLFW_KEY_F1)];
    }
    switch (key) {
        case GLFW_KEY_SPACE:
            return findKeyName("space");
        case GLFW_KEY_TAB:
            return findKeyName("tab");
        case GLFW_KEY_ENTER:
        case GLFW_KEY_KP_ENTER:
            return findKeyName("enter");
        case GLFW_KEY_ESCAPE:
            return findKeyName("escape");
        case GLFW_KEY_BACKSPACE:
            return findKeyName("backspace");
        case GLFW_KEY_DELETE:
            return findKeyName("delete");
        case GLFW_KEY_INSERT:
            return findKeyName("insert");
        case GLFW_KEY_HOME:
            return findKeyName("home");
        case GLFW_KEY_END:
            return findKeyName("end");
        case GLFW_KEY_PAGE_UP:
            return findKeyName("page_up");
        case GLFW_KEY_PAGE_DOWN:
            return findKeyName("page_down");
        case GLFW_KEY_UP:
            return findKeyName("up");
        case GLFW_KEY_DOWN:
            return findKeyName("down");
        case GLFW_KEY_LEFT:
            return findKeyName("left");
        case GLFW_KEY_RIGHT:
            return findKeyName("right");
        case GLFW_KEY_LEFT_SHIFT:
        case GLFW_KEY_RIGHT_SHIFT:
            return findKeyName("shift");
        case GLFW_KEY_LEFT_CONTROL:
        case GLFW_KEY_RIGHT_CONTROL:
            return findKeyName("ctrl");
        case GLFW_KEY_LEFT_ALT:
        case GLFW_KEY_RIGHT_ALT:
            return findKeyName("alt");
        case GLFW_KEY_MINUS:
        case GLFW_KEY_KP_SUBTRACT:
            return findKeyName("minus");
        case GLFW_KEY_EQUAL:
        case GLFW_KEY_KP_ADD:
            return findKeyName("equal");
        case GLFW_KEY_COMMA:
            return findKeyName("comma");
        case GLFW_KEY_PERIOD:
            return findKeyName("period");
        default:
            return {};
    }
}

}  // namespace

GlfwWindow& GlfwWindow::of(GLFWwindow* window) {
    return *static_cast<GlfwWindow*>(glfwLibrary().glfwGetWindowUserPointer(window));
}

GlfwWindow::GlfwWindow(uint32_t width, uint32_t height, const std::string& title) {
    const GlfwLibrary& glfw = glfwLibrary();
    if (glfw.glfwInit() != GLFW_TRUE) {
        throw WindowUnavailable("no display to open a window on (" + lastGlfwError(glfw) + ")");
    }
    glfw.glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfw.glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfw.glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfw.glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfw.glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    // The renderer draws into its own framebuffer object; the window only receives a blit.
    glfw.glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glfw.glfwWindowHint(GLFW_STENCIL_BITS, 0);
    glfw.glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
    window_ = glfw.glfwCreateWindow(static_cast<int>(width), static_cast<int>(height),
                                    title.c_str(), nullptr, nullptr);
    if (window_ == nullptr) {
        const std::string why = lastGlfwError(glfw);
        glfw.glfwTerminate();
        throw WindowUnavailable("cannot open a window with an OpenGL 4.5 core context (" + why +
                                ")");
    }
    glfw.glfwMakeContextCurrent(window_);
    // The viewer paces itself by the scenario's time step; waiting for vertical blank would only
    // add an unmeasured delay.
    glfw.glfwSwapInterval(0);
    std::string error;
    const auto get_proc = glfw.glfwGetProcAddress;
    if (!loadGlFunctions(
            [get_proc](const char* name) { return reinterpret_cast<void*>(get_proc(name)); },
            &error)) {
        glfw.glfwDestroyWindow(window_);
        glfw.glfwTerminate();
        throw WindowUnavailable("the window's OpenGL context: " + error);
    }

    int w = 0, h = 0;
    glfw.glfwGetFramebufferSize(window_, &w, &h);
    fb_width_ = static_cast<uint32_t>(w);
    fb_height_ = static_cast<uint32_t>(h);
    glfw.glfwSetWindowUserPointer(window_, this);
    glfw.glfwSetKeyCallback(window_, [](GLFWwindow* win, int key, int, int action, int) {
        const std::string_view name = keyName(key);
        if (name.empty() || action == GLFW_REPEAT) return;
        WindowEvent e;
        e.type = action == GLFW_PRESS ? WindowEvent::Type::KeyDown : WindowEvent::Type::KeyUp;
        e.key = name;
        of(win).push(e);
    });
    glfw.glfwSetMouseButtonCallback(window_, [](GLFWwindow* win, int button, int action, int) {
        WindowEvent e;
        e.type = action == GLFW_PRESS ? WindowEvent::Type::MouseDown : WindowEvent::Type::MouseUp;
        e.button = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : button == GLFW_MOUSE_BUTTON_RIGHT ? 1 : 2;
        of(win).push(e);
    });
    glfw.glfwSetCursorPosCallback(window_, [](GLFWwindow* win, double x, double y) {
        of(win).push({WindowEvent::Type::CursorMove, {}, 0, x, y});
    });
    glfw.glfwSetScrollCallback(window_, [](GLFWwindow* win, double dx, double dy) {
        of(win).push({WindowEvent::Type::Scroll, {}, 0, dx, dy});
    });
    glfw.glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* win, int fw, int fh) {
        GlfwWindow& self = of(win);
        self.fb_width_ = static_cast<uint32_t>(fw);
        self.fb_height_ = static_cast<uint32_t>(fh);
        self.push(
            {WindowEvent::Type::Resize, {}, 0, static_cast<double>(fw), static_cast<double>(fh)});
    });
    glfw.glfwSetWindowCloseCallback(window_, [](GLFWwindow* win) {
        of(win).push({WindowEvent::Type::Close, {}, 0, 0.0, 0.0});
    });
    try {
        presenter_ = std::make_unique<GlImagePresenter>();
    } catch (...) {
        glfw.glfwDestroyWindow(window_);  // no destructor runs for a half-made window
        glfw.glfwTerminate();
        throw;
    }
}

GlfwWindow::~GlfwWindow() {
    presenter_.reset();  // its GL objects go while the context is still current
    const GlfwLibrary& glfw = glfwLibrary();
    glfw.glfwDestroyWindow(window_);
    glfw.glfwTerminate();
}

std::string GlfwWindow::rendererName() const { return glRendererDescription(); }

std::vector<WindowEvent> GlfwWindow::takeEvents(double wait_s) {
    const GlfwLibrary& glfw = glfwLibrary();
    if (wait_s > 0.0 && queue_.empty()) {
        glfw.glfwWaitEventsTimeout(wait_s);
    } else {
        glfw.glfwPollEvents();
    }
    std::vector<WindowEvent> events;
    events.swap(queue_);
    return events;
}

bool GlfwWindow::closeRequested() const {
    return glfwLibrary().glfwWindowShouldClose(window_) == GLFW_TRUE;
}

void GlfwWindow::requestClose() { glfwLibrary().glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void GlfwWindow::setTitle(const std::string& title) {
    glfwLibrary().glfwSetWindowTitle(window_, title.c_str());
}

void GlfwWindow::setSize(uint32_t width, uint32_t height) {
    glfwLibrary().glfwSetWindowSize(window_, static_cast<int>(width), static_cast<int>(height));
}

void GlfwWindow::present(std::span<const uint8_t> rgba, uint32_t width, uint32_t height) {
    if (fb_width_ == 0 || fb_height_ == 0) return;  // minimised: nothing to show
    presenter_->draw(rgba, width, height, fb_width_, fb_height_);
    glfwLibrary().glfwSwapBuffers(window_);
}

}  // namespace occsim
