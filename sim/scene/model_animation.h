// A glTF model's node hierarchy and its node animations as plain data, and their evaluation:
// sampling a channel at a time (key search, then LINEAR with spherical interpolation for
// rotations, STEP, or CUBICSPLINE) and posing every node visit of the hierarchy. The glTF reader
// (gltf_source.cpp, gltf_animation.cpp) fills these; the world (sim/world/model_copies.cpp)
// evaluates them once per frame per moving copy. Evaluation allocates nothing: its scratch
// buffers are sized once (ModelPoseScratch).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <vector>

namespace occsim {

enum class Interpolation : uint8_t { Linear, Step, CubicSpline };
enum class AnimatedProperty : uint8_t { Translation, Rotation, Scale };

// One sampler: key times (seconds, strictly increasing) and values. Translation and scale use
// xyz, rotation xyzw (glTF's quaternion order). CUBICSPLINE keeps three values per key: the
// in-tangent, the value, the out-tangent (glTF 2.0, appendix C).
struct AnimationSampler {
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times;
    std::vector<glm::dvec4> values;
};

struct AnimationChannel {
    uint32_t sampler = 0;
    uint32_t node = 0;  // a node of the file
    AnimatedProperty property = AnimatedProperty::Translation;
};

struct NodeAnimation {
    std::string name;  // the file's name, or empty
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;  // only channels that move a node
    double duration_s = 0.0;                 // the largest key time of its samplers
};

// A node's rest transform: either a matrix or translation, rotation, scale (animated nodes are
// always TRS, as the glTF specification requires).
struct ModelNode {
    bool has_matrix = false;
    glm::dmat4 matrix{1.0};
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};
};

// A node as the scene hierarchy reaches it; parents come before their children.
struct HierarchyVisit {
    uint32_t node = 0;
    int32_t parent = -1;  // index into AnimatedModel::visits, -1 for a scene root
};

struct AnimatedModel {
    std::vector<ModelNode> nodes;        // every node of the file
    std::vector<HierarchyVisit> visits;  // the scene hierarchy, depth first
    std::vector<uint32_t> object_visit;  // per object of one copy: the visit that draws it
    std::vector<NodeAnimation> animations;
    double scale = 1.0;  // the source's uniform scale, applied to the model's world matrices

    // Per animation, which objects of a copy it moves: an object whose visit or an ancestor
    // visit is the target of one of its channels.
    std::vector<uint8_t> objectsMovedBy(size_t animation) const;
};

// The value of a sampler at time t (seconds); before the first key the first value, after the
// last key the last value. Rotations come out as unit quaternions (xyzw).
glm::dvec4 sampleAt(const AnimationSampler& sampler, double t);

// Spherical interpolation of unit quaternions along the shorter arc (xyzw in a dvec4).
glm::dvec4 slerpXyzw(const glm::dvec4& a, const glm::dvec4& b, double s);

// Buffers for posing one model, sized once for it.
struct ModelPoseScratch {
    std::vector<glm::dvec3> translation;
    std::vector<glm::dquat> rotation;
    std::vector<glm::dvec3> scale;
    std::vector<glm::dmat4> visit_world;  // per visit: the model's world matrix (scale included)

    explicit ModelPoseScratch(const AnimatedModel& model = {});
};

// Poses every visit of the model with animation a at time times[a] when playing[a] is set (the
// others leave their nodes at rest). visit_world gets S(scale) · the hierarchy's world matrix.
void poseModel(const AnimatedModel& model, const std::vector<double>& times,
               const std::vector<uint8_t>& playing, ModelPoseScratch& scratch);

}  // namespace occsim
