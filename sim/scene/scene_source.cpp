#include "sim/scene/scene_source.h"

namespace occsim {

WorldBox sourceBounds(const SourceOutput& source) {
    std::vector<Aabb> mesh_bounds;
    for (const MeshData& mesh : source.meshes) mesh_bounds.push_back(meshBounds(mesh));
    WorldBox bounds;
    for (const PlacedObject& o : source.objects) {
        glm::mat4 m(o.linear);
        m[3] = glm::vec4(0, 0, 0, 1);
        const Aabb box = transformAabb(mesh_bounds.at(o.mesh), m);  // about the origin
        if (isEmpty(box)) continue;
        extend(bounds, glm::dvec3(box.min) + o.position);  // placed in double
        extend(bounds, glm::dvec3(box.max) + o.position);
    }
    return bounds;
}

}  // namespace occsim
