#include "sim/view/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace occsim {
namespace {

// Only the direction to the target matters to the view; a target a few metres ahead keeps the
// spline through recorded keyframes close to the flown directions.
constexpr double kLookDistance = 10.0;
constexpr double kMinSpeed = 0.01, kMaxSpeed = 1e5;

}  // namespace

void FlyCamera::setPose(const CameraPose& pose) {
    position_ = pose.position;
    const glm::dvec3 d = pose.target - pose.position;
    const double length = glm::length(d);
    if (!(length > 0.0)) return;  // keep the heading: a target on the eye has no direction
    yaw_deg_ = glm::degrees(std::atan2(d.x, -d.z));
    pitch_deg_ = std::clamp(glm::degrees(std::asin(std::clamp(d.y / length, -1.0, 1.0))),
                            -kMaxPitchDeg, kMaxPitchDeg);
}

glm::dvec3 FlyCamera::forward() const {
    const double yaw = glm::radians(yaw_deg_), pitch = glm::radians(pitch_deg_);
    return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), -std::cos(pitch) * std::cos(yaw)};
}

CameraPose FlyCamera::pose() const { return {position_, position_ + kLookDistance * forward()}; }

void FlyCamera::turn(double yaw_deg, double pitch_deg) {
    yaw_deg_ = std::remainder(yaw_deg_ + yaw_deg, 360.0);
    pitch_deg_ = std::clamp(pitch_deg_ + pitch_deg, -kMaxPitchDeg, kMaxPitchDeg);
}

void FlyCamera::fly(const FlyInput& input, double seconds) {
    turn(input.turn_right * kTurnRateDegS * seconds, input.turn_up * kTurnRateDegS * seconds);
    const double yaw = glm::radians(yaw_deg_);
    const glm::dvec3 right(std::cos(yaw), 0.0, std::sin(yaw));
    const glm::dvec3 step = double(input.forward) * forward() + double(input.right) * right +
                            double(input.up) * glm::dvec3(0.0, 1.0, 0.0);
    const double length = glm::length(step);
    if (length == 0.0) return;
    // Diagonals are no faster than straight lines.
    const double distance = speed_ * (input.fast ? kFastFactor : 1.0) * seconds;
    position_ += step / length * distance;
}

void FlyCamera::look(double dx_pixels, double dy_pixels) {
    turn(dx_pixels * kLookDegPerPixel, -dy_pixels * kLookDegPerPixel);
}

void FlyCamera::changeSpeed(double notches) {
    speed_ = std::clamp(speed_ * std::pow(kSpeedStep, notches), kMinSpeed, kMaxSpeed);
}

}  // namespace occsim
