#include "sim/world/camera_path.h"

#include <algorithm>
#include <cmath>

namespace occsim {
namespace {

glm::dvec3 catmullRom(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                      const glm::dvec3& p3, double u) {
    const double u2 = u * u, u3 = u2 * u;
    return 0.5 * ((2.0 * p1) + (-p0 + p2) * u + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2 +
                  (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u3);
}

}  // namespace

CameraPose sampleCameraPath(const CameraSpec& camera, double time_s) {
    const auto& keys = camera.keyframes;
    const size_t n = keys.size();
    if (n == 1) return {keys[0].position, keys[0].target};
    const double start = keys.front().time_s, end = keys.back().time_s;
    double t = time_s;
    if (camera.loop && end > start) {
        t = start + std::fmod(t - start, end - start);
        if (t < start) t += end - start;
    }
    if (t <= start) return {keys.front().position, keys.front().target};
    if (t >= end) return {keys.back().position, keys.back().target};

    // Segment i runs from keys[i] to keys[i+1].
    const auto after =
        std::upper_bound(keys.begin(), keys.end(), t,
                         [](double v, const CameraKeyframe& k) { return v < k.time_s; });
    const size_t i = static_cast<size_t>(after - keys.begin()) - 1;
    const double u = (t - keys[i].time_s) / (keys[i + 1].time_s - keys[i].time_s);
    // Neighbours: wrap on a loop (whose last keyframe repeats the first), clamp otherwise.
    auto index = [&](long k) -> size_t {
        const long last = static_cast<long>(n) - 1;
        if (camera.loop) return static_cast<size_t>(((k % last) + last) % last);
        return static_cast<size_t>(std::clamp(k, 0L, last));
    };
    const long li = static_cast<long>(i);
    const CameraKeyframe& k0 = keys[index(li - 1)];
    const CameraKeyframe& k1 = keys[i];
    const CameraKeyframe& k2 = keys[i + 1];
    const CameraKeyframe& k3 = keys[index(li + 2)];
    return {catmullRom(k0.position, k1.position, k2.position, k3.position, u),
            catmullRom(k0.target, k1.target, k2.target, k3.target, u)};
}

glm::dvec3 cameraWorldUp(const glm::dvec3& forward) {
    return std::abs(forward.y) > 0.999 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(0.0, 1.0, 0.0);
}

}  // namespace occsim
