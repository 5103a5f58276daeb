#include "sim/scene/scene_source.h"

namespace occsim {

Aabb sourceBounds(const SourceOutput& source) {
    std::vector<Aabb> mesh_bounds;
    for (const MeshData& mesh : source.meshes) mesh_bounds.push_back(meshBounds(mesh));
    Aabb bounds;
    for (const PlacedObject& o : source.objects) {
        glm::mat4 m(o.linear);
        m[3] = glm::vec4(0, 0, 0, 1);
        Aabb box = transformAabb(mesh_bounds.at(o.mesh), m);
        box.min = glm::vec3(glm::dvec3(box.min) + o.position);
        box.max = glm::vec3(glm::dvec3(box.max) + o.position);
        extend(bounds, box);
    }
    return bounds;
}

}  // namespace occsim
