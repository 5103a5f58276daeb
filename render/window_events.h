// What a window reports to whoever drives it: keys by name, mouse buttons and motion, the wheel,
// a new framebuffer size, a request to close. No window-system types, so that the viewer
// (sim/view/) and its scripted input speak the same events and tests need no window.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace occsim {

struct WindowEvent {
    enum class Type : uint8_t {
        KeyDown,
        KeyUp,
        MouseDown,
        MouseUp,
        CursorMove,
        Scroll,
        Resize,
        Close
    };
    Type type = Type::Close;
    // KeyDown, KeyUp: one of keyNames() (static storage, so events are cheap to copy).
    std::string_view key;
    // MouseDown, MouseUp: 0 left, 1 right, 2 middle.
    int button = 0;
    // CursorMove: the cursor position in pixels; Scroll: the wheel offset (y: one notch = 1);
    // Resize: the new framebuffer size in pixels.
    double x = 0.0, y = 0.0;
};

// Every key name a window reports: "a".."z", "0".."9", "f1".."f12" and named keys ("space",
// "tab", "enter", "escape", "backspace", "shift", "up", ...). Key repeats are not reported.
std::span<const std::string_view> keyNames();
// The canonical name (static storage) when `name` is one of keyNames(); empty otherwise.
std::string_view findKeyName(std::string_view name);

}  // namespace occsim
