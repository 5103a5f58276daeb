// What one scene source (a generator or a glTF file) produces: its meshes, the objects placed
// with them, lanes that movers may follow, and the region its content occupies. The scene builder
// (sim/world/scene_assembly.cpp) concatenates sources into one Scene.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "occsim/culling/geometry/aabb.h"
#include "render/mesh_data.h"
#include "sim/scenario/scene_specs.h"
#include "sim/scenario/view_specs.h"
#include "sim/scene/model_animation.h"

namespace occsim {

// An object of a source: mesh index into SourceOutput::meshes, its position (metres, world) and
// its linear part (rotation, scale, shear) applied in model space first.
struct PlacedObject {
    uint32_t mesh = 0;
    glm::dvec3 position{0.0};
    glm::mat3 linear{1.0f};
    // What a person calls it: the glTF node's name; empty for generated objects (the scene
    // builder names those after their source, Scene::object_names).
    std::string name;
    // The glTF node's own "occsim_occluder" (extras), else empty: the source's role holds.
    std::optional<OccluderRole> occluder;
    // The glTF node's "occsim_occluder_mesh" (extras): a mesh of this source (an index into
    // SourceOutput::meshes) made to occlude for it; empty: none.
    std::optional<uint32_t> occluder_mesh;
};

// Where one copy of a glTF model went: T(origin) · R_y(yaw) places the model (its scale is in
// AnimatedModel::scale).
struct ModelCopyPlacement {
    glm::dvec3 origin{0.0};  // the source's offset plus the copy's origin
    double yaw = 0.0;        // radians about +y
};

struct SourceOutput {
    std::vector<MeshData> meshes;
    std::vector<PlacedObject> objects;
    // Closed loops of points (world, metres) along which things naturally move: streets for
    // cars, aisles for people, walkways for the plant. Movers with motion "path" and no
    // waypoints of their own follow these.
    std::vector<std::vector<glm::dvec3>> lanes;
    WorldBox region;                    // bounds of the content; the default region for movers
    std::vector<std::string> warnings;  // things skipped or approximated, shown to the user
    // glTF sources: the model's hierarchy and animations, and its copies. The objects of copy k
    // are objects[k * n .. (k + 1) * n - 1], n = model->object_visit.size().
    std::shared_ptr<const AnimatedModel> model;
    std::vector<ModelCopyPlacement> model_copies;
    // glTF sources: the file's lights (KHR_lights_punctual) in world space: its directional
    // lights once, its spot lights once per copy.
    std::vector<LightSpec> lights;
};

// Bounds of every object's mesh bounds under its placement.
WorldBox sourceBounds(const SourceOutput& source);

// Builds the source a scenario describes; deterministic for a given spec and seed. Throws
// GltfError for unusable glTF files.
SourceOutput generateSource(const SceneSourceSpec& source, uint64_t seed);

}  // namespace occsim
