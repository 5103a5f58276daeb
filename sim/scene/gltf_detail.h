// Parts of the glTF reader shared by its files (gltf_source.cpp: meshes and the scene graph,
// gltf_accessors.cpp: checked accessor views, gltf_animation.cpp: animations). Internal to the
// scene layer; includes tinygltf.
#pragma once

#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sim/scenario/errors.h"
#include "sim/scenario/scene_specs.h"
#include "sim/scenario/view_specs.h"
#include "sim/scene/model_animation.h"

namespace occsim::gltf_detail {

namespace tg = tinygltf;

[[noreturn]] void fail(const std::string& file, const std::string& reason);

std::string plural(size_t n, const std::string& word);

struct Context {
    const tg::Model& model;
    const std::string& file;
    std::vector<std::string>& warnings;
};

// The bytes of a validated accessor: element i starts at data + i * stride.
struct AccessorView {
    const unsigned char* data = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;
    int type = 0;
    bool normalized = false;
};

// Either a view or the reason the primitive using it has to be skipped.
struct ViewOrSkip {
    std::optional<AccessorView> view;
    std::string skip_reason;
};

// Checks every reference and byte range of accessor `index` (used as `what`); a broken file
// throws, a valid accessor this loader does not read (sparse, no bufferView) is a skip.
ViewOrSkip viewAccessor(const Context& c, int index, const std::string& what);

// The node animations of the file (gltf_animation.cpp). Throws GltfError, with the JSON path,
// for what the glTF specification forbids (key times not increasing, output counts that do not
// match the interpolation, a rotation output that is not VEC4, ...); warns about what is not
// evaluated (morph-target weights, channels without a target node).
std::vector<NodeAnimation> readAnimations(const Context& c);

// A node that carries a light (KHR_lights_punctual), with its world transform.
struct LightNode {
    size_t node = 0;
    int light = -1;
    glm::dmat4 world{1.0};
};

// The light node `index` carries, -1 when none (gltf_lights.cpp). Throws GltfError when its
// extension names no light index.
int nodeLight(const Context& c, const tg::Node& node, size_t index);

// The lights of `nodes` as a scene's lights, positions scaled by `scale` (gltf_lights.cpp):
// directional and spot lights; anything else, or a light index out of range, throws GltfError.
std::vector<LightSpec> convertLights(const Context& c, const std::vector<LightNode>& nodes,
                                     double scale, GltfLights use);

}  // namespace occsim::gltf_detail
