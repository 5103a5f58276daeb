// A window with an OpenGL 4.5 core context, through GLFW loaded at run time (glfw_library.h):
// the viewer's GlContext. The GL entry points come from glfwGetProcAddress; no OSMesa context is
// ever made here. One window per process.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "occsim/culling/contract/input_error.h"
#include "render/gl_context.h"
#include "render/gl_image_presenter.h"
#include "render/window_events.h"

struct GLFWwindow;

namespace occsim {

// No window can be opened here: libglfw is missing, there is no display, or the display offers
// no OpenGL 4.5 core context. what() is one line saying which.
struct WindowUnavailable : InputError {
    using InputError::InputError;
};

class GlfwWindow final : public GlContext {
  public:
    // Opens a window whose framebuffer is about width x height pixels, makes its context current
    // and loads the GL entry points. Throws WindowUnavailable.
    GlfwWindow(uint32_t width, uint32_t height, const std::string& title);
    ~GlfwWindow() override;
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;

    std::string rendererName() const override;

    // The events since the last call. With wait_s > 0 and nothing queued, blocks up to wait_s
    // seconds for one (an idle, paused viewer need not spin).
    std::vector<WindowEvent> takeEvents(double wait_s = 0.0);
    // Set by the window manager's close button (also reported as a Close event) or requestClose().
    bool closeRequested() const;
    void requestClose();

    // The framebuffer size in pixels as last reported (0 x 0 while minimised).
    uint32_t framebufferWidth() const { return fb_width_; }
    uint32_t framebufferHeight() const { return fb_height_; }
    void setTitle(const std::string& title);
    // Asks for a new size; the Resize event follows once the window system has applied it.
    void setSize(uint32_t width, uint32_t height);

    // Shows an RGBA8 image (rows bottom-up) scaled to the framebuffer, then swaps buffers.
    void present(std::span<const uint8_t> rgba, uint32_t width, uint32_t height);

  private:
    static GlfwWindow& of(GLFWwindow* window);
    void push(const WindowEvent& event) { queue_.push_back(event); }

    GLFWwindow* window_ = nullptr;
    uint32_t fb_width_ = 0, fb_height_ = 0;
    std::vector<WindowEvent> queue_;
    std::unique_ptr<GlImagePresenter> presenter_;
};

}  // namespace occsim
