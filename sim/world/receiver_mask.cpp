// See receiver_mask.h.
#include "sim/world/receiver_mask.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace occsim {
namespace {

constexpr double kNoReceiver = -std::numeric_limits<double>::infinity();

// Depths are compared after rounding in double from float boxes: a caster within this many metres
// (relative to the depths' size) of a receiver's far side still counts as nearer.
double depthSlack(double depth) { return 1e-9 * (1.0 + std::abs(depth)); }

}  // namespace

void ReceiverMask::reset(const LightBox& box, uint32_t resolution) {
    box_ = box;
    n_ = std::max<uint32_t>(resolution, 1);
    texel_ = glm::dvec2(box.max - box.min) / static_cast<double>(n_);
    deepest_.assign(size_t{n_} * n_, kNoReceiver);
}

ReceiverMask::TexelRange ReceiverMask::footprint(const glm::dvec3& lo, const glm::dvec3& hi) const {
    TexelRange r;
    if (box_.empty || !(lo.x <= hi.x)) return r;
    glm::dvec3 min, max;
    lightSpaceBounds(box_, lo, hi, min, max);
    if (max.x < box_.min.x || min.x > box_.max.x || max.y < box_.min.y || min.y > box_.max.y) {
        return r;  // beside the light's box: no texel
    }
    // Every texel the footprint touches, its edges included (a point on a texel border counts
    // for both texels).
    auto texel = [this](double v, double origin, double size) {
        const double t = std::floor((v - origin) / size);
        return static_cast<uint32_t>(std::clamp(t, 0.0, static_cast<double>(n_ - 1)));
    };
    const bool flat_x = !(texel_.x > 0.0), flat_y = !(texel_.y > 0.0);
    r.x0 = flat_x ? 0 : texel(min.x, box_.min.x, texel_.x);
    r.x1 = flat_x ? n_ - 1 : texel(max.x, box_.min.x, texel_.x);
    r.y0 = flat_y ? 0 : texel(min.y, box_.min.y, texel_.y);
    r.y1 = flat_y ? n_ - 1 : texel(max.y, box_.min.y, texel_.y);
    r.near_depth = min.z;
    r.far_depth = max.z;
    return r;
}

void ReceiverMask::addReceiver(const glm::dvec3& point, double margin_m) {
    const TexelRange r = footprint(point - margin_m, point + margin_m);
    for (uint32_t y = r.y0; y <= r.y1 && r.x0 <= r.x1; ++y) {
        double* row = deepest_.data() + size_t{y} * n_;
        for (uint32_t x = r.x0; x <= r.x1; ++x) row[x] = std::max(row[x], r.far_depth);
    }
}

bool ReceiverMask::mayShadow(const Aabb& box, const glm::dvec3& culling_origin) const {
    if (!(box.min.x <= box.max.x)) return false;
    const TexelRange r =
        footprint(glm::dvec3(box.min) + culling_origin, glm::dvec3(box.max) + culling_origin);
    const double near = r.near_depth - depthSlack(r.near_depth);
    for (uint32_t y = r.y0; y <= r.y1 && r.x0 <= r.x1; ++y) {
        const double* row = deepest_.data() + size_t{y} * n_;
        for (uint32_t x = r.x0; x <= r.x1; ++x) {
            if (row[x] >= near) return true;
        }
    }
    return false;
}

uint32_t ReceiverMask::coveredTexels() const {
    return static_cast<uint32_t>(
        std::count_if(deepest_.begin(), deepest_.end(), [](double d) { return d != kNoReceiver; }));
}

}  // namespace occsim
