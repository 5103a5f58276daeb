// A recorded camera flight as a scenario file: the loaded scenario, unchanged but for the camera
// path (one keyframe per recorded frame, at frame * dt, so a headless run replays the flown frames
// exactly), the frame count, and what a new path invalidates or a new folder moves:
// - "frames" becomes the number of recorded frames; "warmup_frames" and "expect"/"frames" are
//   clamped below it; the camera's "loop", "orbit" and "fly" go, its lens (fov_y, near, far) stays.
// - glTF source paths are rewritten to resolve from the new file's folder (relative when
//   possible); "name", when given, becomes the new file's stem.
// - "expect"/"baseline" goes: the old baseline pins the old path's per-frame counts. The new
//   scenario's baseline is created with `occsim regress FILE --update`.
// Everything else keeps its text, keys in their original order.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "sim/scenario/scenario.h"

namespace occsim {

// `original_text` is the file `original` was parsed from. Keyframes must be non-empty, with the
// times the viewer gives them (frame * original.dt_s). The result is checked by parsing it as if
// it were at `new_file` (whose folder must exist when the scenario names files); a failure there
// throws ScenarioError.
std::string recordedScenarioText(const std::string& original_text, const Scenario& original,
                                 std::span<const CameraKeyframe> keyframes,
                                 const std::filesystem::path& new_file);

// The same, written atomically to new_file (creating its folder).
void writeRecordedScenario(const std::string& original_text, const Scenario& original,
                           std::span<const CameraKeyframe> keyframes,
                           const std::filesystem::path& new_file);

}  // namespace occsim
