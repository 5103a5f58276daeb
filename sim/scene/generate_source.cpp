// Building one scene source from its spec: the teapot field of both papers here, the other
// generators and glTF files in their own files.
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "occsim/culling/geometry/random.h"
#include "sim/scene/generators.h"
#include "sim/scene/gltf_source.h"
#include "sim/scene/scene_source.h"
#include "sim/scene/teapot.h"

namespace occsim {
namespace {

SourceOutput generateTeapotField(const TeapotFieldSpec& spec, uint64_t seed) {
    SourceOutput out;
    out.meshes.push_back(tessellateTeapot(spec.tessellation));
    out.region = spec.region;
    Rng rng(seed);
    const glm::dvec3 lo(spec.region.min), hi(spec.region.max);
    for (uint32_t i = 0; i < spec.count; ++i) {
        PlacedObject object;
        object.position = {rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y),
                           rng.uniform(lo.z, hi.z)};
        const auto yaw = static_cast<float>(rng.uniform(0.0, 2.0 * std::numbers::pi));
        const auto scale = static_cast<float>(rng.uniform(spec.size_min_m, spec.size_max_m));
        object.linear = glm::mat3(glm::rotate(glm::mat4(1.0f), yaw, glm::vec3(0, 1, 0))) * scale;
        out.objects.push_back(object);
    }
    return out;
}

}  // namespace

SourceOutput generateSource(const SceneSourceSpec& source, uint64_t seed) {
    switch (source.type) {
        case SourceType::Teapots:
            return generateTeapotField(std::get<TeapotFieldSpec>(source.spec), seed);
        case SourceType::Gltf:
            return loadGltfSource(std::get<GltfSourceSpec>(source.spec), seed);
        case SourceType::City:
            return generateCity(std::get<CitySpec>(source.spec), seed);
        case SourceType::Library:
            return generateLibrary(std::get<LibrarySpec>(source.spec), seed);
        case SourceType::Plant:
            return generatePlant(std::get<PlantSpec>(source.spec), seed);
    }
    return {};
}

}  // namespace occsim
