// glTF 2.0 scenes (.gltf with external or embedded buffers, and .glb) as a scene source. Every
// mesh-bearing node of the default scene becomes an object with its world transform (hierarchy
// flattened); a mesh used by several nodes is converted once and shared. Only indexed or
// non-indexed TRIANGLES primitives with POSITION are used (TRIANGLE_STRIP and TRIANGLE_FAN are
// converted to lists); other parts (other primitive modes, skins, morph targets, cameras) are
// skipped with a warning naming them. Node animations are read and checked (gltf_animation.cpp)
// and returned with the hierarchy in SourceOutput::model; the world evaluates them. See
// docs/scenario-gltf.md for the scenario keys.
#pragma once

#include <cstdint>

#include "sim/scenario/errors.h"
#include "sim/scenario/scene_specs.h"
#include "sim/scene/scene_source.h"

namespace occsim {

// Throws GltfError. `seed` drives random replication.
SourceOutput loadGltfSource(const GltfSourceSpec& spec, uint64_t seed);

}  // namespace occsim
