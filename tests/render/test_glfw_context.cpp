// The viewer's window (render/glfw_context.h) where none can be opened: one line saying why, as
// bad input. Windows that open are tested under xvfb-run through `occsim view`
// (tests/system/test_view_window.cpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>
#include <type_traits>

#include "render/glfw_context.h"

namespace occsim {
namespace {

// Unsets an environment variable for the scope of a test and puts the old value back.
class UnsetVariable {
  public:
    explicit UnsetVariable(const char* name) : name_(name) {
        if (const char* value = std::getenv(name)) old_ = value;
        ::unsetenv(name);
    }
    ~UnsetVariable() {
        if (old_) ::setenv(name_, old_->c_str(), 1);
    }
    UnsetVariable(const UnsetVariable&) = delete;
    UnsetVariable& operator=(const UnsetVariable&) = delete;

  private:
    const char* name_;
    std::optional<std::string> old_;
};

TEST(GlfwWindow, WithoutADisplayTheWindowIsRefusedInOneLineAsBadInput) {
    const UnsetVariable display("DISPLAY");
    const UnsetVariable wayland("WAYLAND_DISPLAY");
    try {
        GlfwWindow window(64, 48, "no display");
        FAIL() << "a window opened without a display";
    } catch (const WindowUnavailable& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        // Either GLFW is there and finds no display, or the library itself is missing.
        EXPECT_TRUE(what.rfind("no display to open a window on (", 0) == 0 ||
                    what.find("libglfw") != std::string::npos)
            << what;
    }
    EXPECT_TRUE((std::is_base_of_v<InputError, WindowUnavailable>)) << "exit 2, not a crash";
}

}  // namespace
}  // namespace occsim
