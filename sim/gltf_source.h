// glTF 2.0 scenes (.gltf with external or embedded buffers, and .glb) as a scene source. Every
// mesh-bearing node of the default scene becomes an object with its world transform (hierarchy
// flattened); a mesh used by several nodes is converted once and shared. Only indexed or
// non-indexed TRIANGLES primitives with POSITION are used (TRIANGLE_STRIP and TRIANGLE_FAN are
// converted to lists); other parts (other primitive modes, skins, morph targets, cameras) are
// skipped with a warning naming them. See docs/scenario-gltf.md for the scenario keys.
#pragma once

#include "sim/scene_source.h"

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace occsim {

// Optional replication so that a small model can make a large scene.
struct GltfReplication {
    enum class Mode : uint8_t { None, Grid, Random };
    Mode mode = Mode::None;
    uint32_t count_x = 1, count_z = 1;  // grid: copies along x and z
    double spacing_m = 0.0;             // grid: distance between copies (0 = model size + 10%)
    uint32_t count = 1;                 // random: number of copies
    Aabb region;                        // random: where copies are placed (their origins)
    bool random_yaw = true;             // random: rotate each copy about y
};

struct GltfSourceSpec {
    std::filesystem::path path;       // resolved against the scenario file's folder
    double scale = 1.0;               // uniform scale applied to the whole model
    glm::dvec3 offset{0.0};           // translation applied after scaling (metres)
    GltfReplication replicate;
};

// A glTF file that cannot be used: one line naming the file and tinygltf's (or our) reason.
class GltfError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws GltfError. `seed` drives random replication.
SourceOutput loadGltfSource(const GltfSourceSpec& spec, uint64_t seed);

}  // namespace occsim
