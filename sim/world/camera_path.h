// A camera path through keyframes: position and look-at target interpolated with Catmull-Rom
// splines over time (seconds of simulation time), held at the ends or looped.
#pragma once

#include <glm/glm.hpp>

#include "sim/scenario/scenario.h"

namespace occsim {

struct CameraPose {
    glm::dvec3 position{0.0};
    glm::dvec3 target{0.0, 0.0, -1.0};
};

// Keyframes must be non-empty with strictly increasing times (the parser guarantees it).
CameraPose sampleCameraPath(const CameraSpec& camera, double time_s);

// The world direction a camera looking along `forward` (unit) takes as up: +y, or +z when it
// looks straight up or down (where y cannot be). The renderer's camera, the stereo eyes and a
// light's fit to the camera's frustum all build the camera's axes from it.
glm::dvec3 cameraWorldUp(const glm::dvec3& forward);

}  // namespace occsim
