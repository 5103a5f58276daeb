// Scripted input for the viewer (`occsim view --script FILE`): key presses, mouse drags, the
// wheel and window resizes at chosen frames, fed through the same event handling as a person's
// input, so a test can drive the window headless under xvfb-run. docs/viewer.md has the format:
//
//   # comment                 blank lines and text after '#' are ignored
//   wait N                    N frames pass (N >= 1)
//   press KEY[+KEY...]        press and release, e.g. "press b", "press shift+tab"
//   down KEY / up KEY         press / release one key (for several keys held at once)
//   hold KEY N                down, N frames, up
//   drag DX DY                a mouse drag by DX, DY pixels (looks around)
//   wheel N                   N wheel notches (negative: slower)
//   resize W H                ask for a W x H window (the viewer waits for it, 5 s at most)
//   quit                      close the window (also implied after the last line)
//
// Everything but wait and hold applies before the next frame. Parsing is strict: a mistake is one
// line naming the file, the line number and what was expected.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "occsim/culling/contract/input_error.h"
#include "render/window_events.h"

namespace occsim {

struct ScriptError : InputError {
    using InputError::InputError;
};

struct ScriptStep {
    enum class Kind : uint8_t { Event, Wait, Resize, Quit };
    Kind kind = Kind::Wait;
    WindowEvent event;               // Event
    uint32_t frames = 0;             // Wait
    uint32_t width = 0, height = 0;  // Resize
};

struct ViewScript {
    std::filesystem::path file;
    std::vector<ScriptStep> steps;
};

// Throws ScriptError "FILE:LINE: ...".
ViewScript parseViewScript(const std::string& text, const std::filesystem::path& file);
ViewScript readViewScript(const std::filesystem::path& file);

// Plays a script frame by frame.
class ScriptPlayer {
  public:
    explicit ScriptPlayer(ViewScript script) : script_(std::move(script)) {}

    struct FrameInput {
        std::vector<WindowEvent> events;
        std::optional<std::pair<uint32_t, uint32_t>> resize;
        bool quit = false;  // close the window after this frame
    };
    // The input for the next frame.
    FrameInput next();

  private:
    ViewScript script_;
    size_t position_ = 0;
    uint32_t waiting_ = 0;  // frames of the current wait still to pass
};

}  // namespace occsim
