// What each key does in the viewer: the one table that the key handling, the on-screen help and
// docs/viewer.md follow. Keys are the names of render/window_events.h.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace occsim {

enum class ViewAction : uint8_t {
    None,
    Quit,
    TogglePause,
    Step,              // one frame while paused
    Restart,           // the world, the path and the culler back to frame 0
    NextAlgorithm,     // shift: the previous one
    SelectAlgorithm,   // digits 1-9: the algorithm at that place in the list
    ToggleBoxes,       // node bounding boxes, coloured by what the culler did
    ToggleBirdsEye,    // the tree and the frustum from above
    ToggleError,       // ground truth every frame, error pixels on screen
    ToggleValidation,  // missed, drawn-while-hidden and culled objects over the frame
    ToggleCameraMode,  // follow the scenario's path / fly by hand
    ToggleRecording,   // record the hand-flown camera; on stop, write a scenario
    Screenshot,
    ToggleHelp,
    TogglePanel,  // the text panel (for clean screenshots)
};

struct KeyBinding {
    std::string_view keys;  // as shown in help ("space", "1-9", "shift+tab")
    ViewAction action;
    std::string_view description;  // one short line
};

// Every action key, in the order help lists them.
std::span<const KeyBinding> actionKeys();

// The held keys that fly the camera, for help (they are not actions: they act while held).
struct FlyKeyHelp {
    std::string_view keys;
    std::string_view description;
};
std::span<const FlyKeyHelp> flyKeys();

// The action of a key press; for SelectAlgorithm, *index is the algorithm's place (0-based).
// Shift is not part of it: NextAlgorithm goes backwards while shift is held.
ViewAction actionForKey(std::string_view key, uint32_t* index);

}  // namespace occsim
