#include "sim/view/key_bindings.h"

#include <array>

namespace occsim {
namespace {

constexpr std::array<KeyBinding, 15> kActionKeys = {{
    {"space", ViewAction::TogglePause, "pause / resume"},
    {"n", ViewAction::Step, "one frame (while paused)"},
    {"backspace", ViewAction::Restart, "restart from frame 0"},
    {"tab", ViewAction::NextAlgorithm, "next algorithm (shift+tab: previous)"},
    {"1-9", ViewAction::SelectAlgorithm, "algorithm by its place in the list"},
    {"b", ViewAction::ToggleBoxes, "node boxes by what the culler did"},
    {"m", ViewAction::ToggleBirdsEye, "the tree and the frustum from above"},
    {"g", ViewAction::ToggleError, "ground truth and error pixels"},
    {"v", ViewAction::ToggleValidation, "validation: missed red, drawn hidden yellow, culled grey"},
    {"c", ViewAction::ToggleCameraMode, "follow the path / fly by hand"},
    {"r", ViewAction::ToggleRecording, "record the flight / stop and save a scenario"},
    {"p", ViewAction::Screenshot, "screenshot (PNG)"},
    {"h", ViewAction::ToggleHelp, "this help"},
    {"o", ViewAction::TogglePanel, "the text panel on / off"},
    {"escape", ViewAction::Quit, "quit"},
}};

constexpr std::array<FlyKeyHelp, 6> kFlyKeys = {{
    {"w a s d", "fly forward, left, back, right"},
    {"e q", "up, down"},
    {"shift", "four times faster"},
    {"arrows", "turn"},
    {"mouse drag", "look around"},
    {"wheel", "flying speed"},
}};

}  // namespace

std::span<const KeyBinding> actionKeys() { return kActionKeys; }

std::span<const FlyKeyHelp> flyKeys() { return kFlyKeys; }

ViewAction actionForKey(std::string_view key, uint32_t* index) {
    if (key.size() == 1 && key[0] >= '1' && key[0] <= '9') {
        if (index) *index = static_cast<uint32_t>(key[0] - '1');
        return ViewAction::SelectAlgorithm;
    }
    for (const KeyBinding& b : kActionKeys) {
        if (b.keys == key) return b.action;
    }
    return ViewAction::None;
}

}  // namespace occsim
