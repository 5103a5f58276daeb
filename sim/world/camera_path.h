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

}  // namespace occsim
