// PLACEHOLDER while the loader is being written; replaced before the issue is resolved.
#include "sim/gltf_source.h"

namespace occsim {

SourceOutput loadGltfSource(const GltfSourceSpec& spec, uint64_t) {
    throw GltfError(spec.path.string() + ": the glTF loader is not implemented yet");
}

}  // namespace occsim
