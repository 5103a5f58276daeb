#include "sim/scene/model_animation.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace occsim {
namespace {

glm::dvec4 normalizedQuat(const glm::dvec4& q) {
    const double len = glm::length(q);
    return len > 0.0 && std::isfinite(len) ? q / len : glm::dvec4(0, 0, 0, 1);
}

// Key k with times[k] <= t < times[k + 1]; the caller has handled t outside the keys.
size_t keyBefore(const std::vector<double>& times, double t) {
    const auto it = std::upper_bound(times.begin(), times.end(), t);
    return static_cast<size_t>(it - times.begin()) - 1;
}

glm::dvec4 valueOfKey(const AnimationSampler& s, size_t k) {
    return s.interpolation == Interpolation::CubicSpline ? s.values[3 * k + 1] : s.values[k];
}

}  // namespace

glm::dvec4 slerpXyzw(const glm::dvec4& a, const glm::dvec4& b_in, double s) {
    glm::dvec4 b = b_in;
    double d = glm::dot(a, b);
    if (d < 0.0) {  // q and -q are the same rotation: take the shorter way round
        b = -b;
        d = -d;
    }
    if (d > 0.9995) return normalizedQuat(a + s * (b - a));  // nearly equal: sin(theta) ~ 0
    const double theta = std::acos(std::min(d, 1.0));
    const double sin_theta = std::sin(theta);
    return normalizedQuat((std::sin((1.0 - s) * theta) / sin_theta) * a +
                          (std::sin(s * theta) / sin_theta) * b);
}

glm::dvec4 sampleAt(const AnimationSampler& sampler, double t) {
    const std::vector<double>& times = sampler.times;
    if (times.empty()) return glm::dvec4(0.0);
    if (!(t > times.front())) return valueOfKey(sampler, 0);
    if (t >= times.back()) return valueOfKey(sampler, times.size() - 1);
    const size_t k = keyBefore(times, t);
    const double interval = times[k + 1] - times[k];
    const double s = (t - times[k]) / interval;
    switch (sampler.interpolation) {
        case Interpolation::Step:
            return sampler.values[k];
        case Interpolation::Linear:
            return sampler.values[k] + s * (sampler.values[k + 1] - sampler.values[k]);
        case Interpolation::CubicSpline: {
            // Hermite spline; tangents are per second, so they are scaled by the key interval.
            const glm::dvec4& v0 = sampler.values[3 * k + 1];
            const glm::dvec4& out0 = sampler.values[3 * k + 2];
            const glm::dvec4& in1 = sampler.values[3 * (k + 1)];
            const glm::dvec4& v1 = sampler.values[3 * (k + 1) + 1];
            const double s2 = s * s, s3 = s2 * s;
            return (2 * s3 - 3 * s2 + 1) * v0 + interval * (s3 - 2 * s2 + s) * out0 +
                   (-2 * s3 + 3 * s2) * v1 + interval * (s3 - s2) * in1;
        }
    }
    return sampler.values[k];
}

namespace {

// Rotation channels interpolate on the sphere (LINEAR) or are normalised (CUBICSPLINE), so a
// posed node always has a unit quaternion.
glm::dvec4 sampleRotation(const AnimationSampler& sampler, double t) {
    const std::vector<double>& times = sampler.times;
    if (sampler.interpolation == Interpolation::Linear && t > times.front() && t < times.back()) {
        const size_t k = keyBefore(times, t);
        const double s = (t - times[k]) / (times[k + 1] - times[k]);
        return slerpXyzw(normalizedQuat(sampler.values[k]), normalizedQuat(sampler.values[k + 1]),
                         s);
    }
    return normalizedQuat(sampleAt(sampler, t));
}

glm::dmat4 restMatrix(const ModelNode& node, const glm::dvec3& t, const glm::dquat& r,
                      const glm::dvec3& s) {
    if (node.has_matrix) return node.matrix;
    return glm::scale(glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(r), s);
}

}  // namespace

std::vector<uint8_t> AnimatedModel::objectsMovedBy(size_t animation) const {
    std::vector<uint8_t> targeted(nodes.size(), 0);
    for (const AnimationChannel& c : animations[animation].channels) targeted[c.node] = 1;
    std::vector<uint8_t> visit_moved(visits.size(), 0);
    for (size_t v = 0; v < visits.size(); ++v) {
        const HierarchyVisit& visit = visits[v];
        visit_moved[v] = targeted[visit.node] ||
                         (visit.parent >= 0 && visit_moved[static_cast<size_t>(visit.parent)]);
    }
    std::vector<uint8_t> moved(object_visit.size(), 0);
    for (size_t o = 0; o < object_visit.size(); ++o) moved[o] = visit_moved[object_visit[o]];
    return moved;
}

ModelPoseScratch::ModelPoseScratch(const AnimatedModel& model)
    : translation(model.nodes.size()),
      rotation(model.nodes.size()),
      scale(model.nodes.size()),
      visit_world(model.visits.size()) {}

void poseModel(const AnimatedModel& model, const std::vector<double>& times,
               const std::vector<uint8_t>& playing, ModelPoseScratch& scratch) {
    for (size_t n = 0; n < model.nodes.size(); ++n) {
        scratch.translation[n] = model.nodes[n].translation;
        scratch.rotation[n] = model.nodes[n].rotation;
        scratch.scale[n] = model.nodes[n].scale;
    }
    for (size_t a = 0; a < model.animations.size(); ++a) {
        if (!playing[a]) continue;
        const NodeAnimation& animation = model.animations[a];
        for (const AnimationChannel& c : animation.channels) {
            const AnimationSampler& sampler = animation.samplers[c.sampler];
            switch (c.property) {
                case AnimatedProperty::Translation:
                    scratch.translation[c.node] = glm::dvec3(sampleAt(sampler, times[a]));
                    break;
                case AnimatedProperty::Scale:
                    scratch.scale[c.node] = glm::dvec3(sampleAt(sampler, times[a]));
                    break;
                case AnimatedProperty::Rotation: {
                    const glm::dvec4 q = sampleRotation(sampler, times[a]);
                    scratch.rotation[c.node] = glm::dquat(q.w, q.x, q.y, q.z);
                    break;
                }
            }
        }
    }
    const glm::dmat4 model_scale = glm::scale(glm::dmat4(1.0), glm::dvec3(model.scale));
    for (size_t v = 0; v < model.visits.size(); ++v) {
        const HierarchyVisit& visit = model.visits[v];
        const glm::dmat4 local =
            restMatrix(model.nodes[visit.node], scratch.translation[visit.node],
                       scratch.rotation[visit.node], scratch.scale[visit.node]);
        const glm::dmat4& parent = visit.parent >= 0
                                       ? scratch.visit_world[static_cast<size_t>(visit.parent)]
                                       : model_scale;
        scratch.visit_world[v] = parent * local;
    }
}

}  // namespace occsim
