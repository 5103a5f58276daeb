// glTF node animations read into plain data (sim/scene/model_animation.h), checked against the
// glTF 2.0 specification (section 3.11, "Animations"): what it forbids is an error naming the
// JSON path; what occsim does not evaluate (morph-target weights, channels without a target
// node, extension paths, sparse accessors) is a warning, never dropped in silence.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "sim/scene/gltf_detail.h"

namespace occsim::gltf_detail {
namespace {

std::string animationLabel(const tg::Model& m, size_t a) {
    const std::string& name = m.animations[a].name;
    return name.empty() ? "animation #" + std::to_string(a) : "animation '" + name + "'";
}

std::string samplerPath(size_t a, size_t s) {
    return "/animations/" + std::to_string(a) + "/samplers/" + std::to_string(s);
}

std::string channelPath(size_t a, size_t ch) {
    return "/animations/" + std::to_string(a) + "/channels/" + std::to_string(ch);
}

// Component k of element i as a double: floats as they are, normalised integers mapped to
// [-1, 1] or [0, 1] (glTF 2.0, 3.11: rotations may be stored that way).
double component(const AccessorView& v, size_t i, size_t k) {
    const unsigned char* p = v.data + i * v.stride;
    switch (v.component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t c;
            std::memcpy(&c, p + k, 1);
            return std::max(c / 127.0, -1.0);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return p[k] / 255.0;
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t c;
            std::memcpy(&c, p + 2 * k, 2);
            return std::max(c / 32767.0, -1.0);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t c;
            std::memcpy(&c, p + 2 * k, 2);
            return c / 65535.0;
        }
        default: {
            float c;
            std::memcpy(&c, p + 4 * k, 4);
            return c;
        }
    }
}

std::string typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        default:
            return "type " + std::to_string(type);
    }
}

// A sampler as read, before any channel says what it animates.
struct RawSampler {
    AnimationSampler sampler;
    std::optional<AccessorView> output;
    bool usable = false;  // false: sparse or bufferless accessors (warned about)
};

RawSampler readSampler(const Context& c, size_t a, size_t s) {
    const tg::AnimationSampler& gs = c.model.animations[a].samplers[s];
    const std::string path = samplerPath(a, s);
    RawSampler raw;
    if (gs.interpolation == "LINEAR" || gs.interpolation.empty()) {
        raw.sampler.interpolation = Interpolation::Linear;
    } else if (gs.interpolation == "STEP") {
        raw.sampler.interpolation = Interpolation::Step;
    } else if (gs.interpolation == "CUBICSPLINE") {
        raw.sampler.interpolation = Interpolation::CubicSpline;
    } else {
        fail(c.file,
             path + "/interpolation: expected \"LINEAR\", \"STEP\" or \"CUBICSPLINE\", got \"" +
                 gs.interpolation + "\"");
    }
    const ViewOrSkip input = viewAccessor(c, gs.input, path + "/input");
    const ViewOrSkip output = viewAccessor(c, gs.output, path + "/output");
    if (!input.view || !output.view) {
        c.warnings.push_back(c.file + ": " + path + ": not evaluated (" +
                             (input.view ? output.skip_reason : input.skip_reason) + ")");
        return raw;
    }
    const AccessorView& in = *input.view;
    if (in.type != TINYGLTF_TYPE_SCALAR || in.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        fail(c.file,
             path + "/input: key times must be a SCALAR FLOAT accessor, got " + typeName(in.type));
    }
    if (in.count == 0) fail(c.file, path + "/input: a sampler needs at least one key");
    for (size_t k = 0; k < in.count; ++k) {
        const double t = component(in, k, 0);
        if (!std::isfinite(t) || t < 0.0) {
            fail(c.file, path + "/input: key " + std::to_string(k) + " is at " + std::to_string(t) +
                             " s; key times must be finite and not negative");
        }
        if (k > 0 && !(t > raw.sampler.times.back())) {
            fail(c.file, path + "/input: key times must increase, but key " + std::to_string(k) +
                             " (" + std::to_string(t) + " s) is not after key " +
                             std::to_string(k - 1) + " (" +
                             std::to_string(raw.sampler.times.back()) + " s)");
        }
        raw.sampler.times.push_back(t);
    }
    raw.output = output.view;
    raw.usable = true;
    return raw;
}

// The sampler's values for a channel animating `property`, checked against what the
// specification requires of its type and count.
void readValues(const Context& c, size_t a, size_t s, AnimatedProperty property, RawSampler& raw) {
    if (!raw.sampler.values.empty()) return;  // already read for another channel
    const AccessorView& out = *raw.output;
    const std::string path = samplerPath(a, s) + "/output";
    const bool rotation = property == AnimatedProperty::Rotation;
    const int wanted_type = rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
    const char* what = rotation                              ? "rotation"
                       : property == AnimatedProperty::Scale ? "scale"
                                                             : "translation";
    if (out.type != wanted_type) {
        fail(c.file, path + ": a " + what + " output must be " + typeName(wanted_type) + ", got " +
                         typeName(out.type));
    }
    const bool float_components = out.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool normalized_ints = rotation && out.normalized &&
                                 out.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT &&
                                 out.component_type != TINYGLTF_COMPONENT_TYPE_INT;
    if (!float_components && !normalized_ints) {
        fail(c.file, path + std::string(": a ") + what + " output must be FLOAT" +
                         (rotation ? " or normalized (unsigned) byte or short" : ""));
    }
    const size_t keys = raw.sampler.times.size();
    const size_t per_key = raw.sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
    if (out.count != keys * per_key) {
        fail(c.file,
             path + ": has " + std::to_string(out.count) + " values, but " + std::to_string(keys) +
                 " keys with " +
                 (per_key == 3 ? "CUBICSPLINE need 3 per key (in-tangent, value, out-tangent): "
                               : "LINEAR or STEP need one per key: ") +
                 std::to_string(keys * per_key));
    }
    const size_t components = rotation ? 4 : 3;
    for (size_t i = 0; i < out.count; ++i) {
        glm::dvec4 v(0.0);
        for (size_t k = 0; k < components; ++k) v[static_cast<int>(k)] = component(out, i, k);
        if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) &&
              std::isfinite(v.w))) {
            fail(c.file, path + ": value " + std::to_string(i) + " is not finite");
        }
        raw.sampler.values.push_back(v);
    }
}

}  // namespace

std::vector<NodeAnimation> readAnimations(const Context& c) {
    const tg::Model& m = c.model;
    std::vector<NodeAnimation> animations;
    for (size_t a = 0; a < m.animations.size(); ++a) {
        const tg::Animation& ga = m.animations[a];
        const std::string label = animationLabel(m, a);
        std::vector<RawSampler> samplers;
        for (size_t s = 0; s < ga.samplers.size(); ++s) samplers.push_back(readSampler(c, a, s));
        NodeAnimation animation;
        animation.name = ga.name;
        size_t weights = 0, untargeted = 0;
        std::map<std::string, size_t> other_paths;
        std::vector<uint8_t> used(samplers.size(), 0);
        for (size_t ch = 0; ch < ga.channels.size(); ++ch) {
            const tg::AnimationChannel& gc = ga.channels[ch];
            const std::string path = channelPath(a, ch);
            if (gc.sampler < 0 || static_cast<size_t>(gc.sampler) >= samplers.size()) {
                fail(c.file, path + "/sampler: refers to sampler " + std::to_string(gc.sampler) +
                                 ", but " + label + " has " + plural(samplers.size(), "sampler"));
            }
            if (gc.target_node < 0) {
                ++untargeted;
                continue;
            }
            if (static_cast<size_t>(gc.target_node) >= m.nodes.size()) {
                fail(c.file, path + "/target/node: refers to node " +
                                 std::to_string(gc.target_node) + ", but the file has " +
                                 plural(m.nodes.size(), "node"));
            }
            AnimatedProperty property;
            if (gc.target_path == "translation") {
                property = AnimatedProperty::Translation;
            } else if (gc.target_path == "rotation") {
                property = AnimatedProperty::Rotation;
            } else if (gc.target_path == "scale") {
                property = AnimatedProperty::Scale;
            } else if (gc.target_path == "weights") {
                ++weights;
                continue;
            } else {
                ++other_paths[gc.target_path];
                continue;
            }
            if (!m.nodes[static_cast<size_t>(gc.target_node)].matrix.empty()) {
                fail(c.file, path + "/target/node: node " + std::to_string(gc.target_node) +
                                 " has a matrix; the glTF specification allows only translation, "
                                 "rotation and scale on an animated node");
            }
            const auto s = static_cast<size_t>(gc.sampler);
            if (!samplers[s].usable) continue;  // warned about when read
            readValues(c, a, s, property, samplers[s]);
            used[s] = 1;
            animation.channels.push_back(
                {static_cast<uint32_t>(s), static_cast<uint32_t>(gc.target_node), property});
        }
        for (size_t s = 0; s < samplers.size(); ++s) {
            if (used[s]) {
                animation.duration_s =
                    std::max(animation.duration_s, samplers[s].sampler.times.back());
            }
            animation.samplers.push_back(std::move(samplers[s].sampler));
        }
        if (weights > 0) {
            c.warnings.push_back(c.file + ": " + label + ": " + plural(weights, "channel") +
                                 " animating morph-target weights not evaluated (the base "
                                 "positions are drawn)");
        }
        if (untargeted > 0) {
            c.warnings.push_back(c.file + ": " + label + ": ignored " +
                                 plural(untargeted, "channel") + " without a target node");
        }
        for (const auto& [name, n] : other_paths) {
            c.warnings.push_back(c.file + ": " + label + ": ignored " + plural(n, "channel") +
                                 " with the target path '" + name + "'");
        }
        animations.push_back(std::move(animation));
    }
    return animations;
}

}  // namespace occsim::gltf_detail
