// The hand-flown camera: a position, a heading (yaw) and a pitch, moved by held keys at a speed
// the wheel changes, turned by mouse drags and the arrow keys. y is up; yaw 0 looks down -z and
// grows to the right; pitch is kept within +-89 degrees so that "up" stays defined.
#pragma once

#include <glm/glm.hpp>

#include "sim/world/camera_path.h"

namespace occsim {

// What the held keys ask for this frame; each axis -1, 0 or 1.
struct FlyInput {
    int forward = 0;                  // w / s
    int right = 0;                    // d / a
    int up = 0;                       // e / q
    int turn_right = 0, turn_up = 0;  // arrow keys
    bool fast = false;                // shift
    bool moving() const {
        return forward != 0 || right != 0 || up != 0 || turn_right != 0 || turn_up != 0;
    }
};

class FlyCamera {
  public:
    static constexpr double kMaxPitchDeg = 89.0;
    static constexpr double kFastFactor = 4.0;
    static constexpr double kTurnRateDegS = 90.0;    // arrow keys
    static constexpr double kLookDegPerPixel = 0.2;  // mouse drags
    static constexpr double kSpeedStep = 1.25;       // per wheel notch

    explicit FlyCamera(double speed_mps = 5.0) : speed_(speed_mps) {}

    // Takes over a pose (the path's, when the user starts flying): position and looking direction.
    void setPose(const CameraPose& pose);
    // The pose, looking at a point one look distance ahead.
    CameraPose pose() const;
    glm::dvec3 position() const { return position_; }
    glm::dvec3 forward() const;

    // Moves and turns for `seconds` of held keys.
    void fly(const FlyInput& input, double seconds);
    // A mouse drag of (dx, dy) pixels: right turns right, down looks down.
    void look(double dx_pixels, double dy_pixels);
    // Wheel notches (positive: faster).
    void changeSpeed(double notches);
    double speed() const { return speed_; }

  private:
    void turn(double yaw_deg, double pitch_deg);

    glm::dvec3 position_{0.0};
    double yaw_deg_ = 0.0, pitch_deg_ = 0.0;
    double speed_;
};

}  // namespace occsim
