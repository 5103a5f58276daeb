// libFuzzer target: the glTF loading path (tinygltf, then accessors, primitives, node hierarchy,
// instancing and placement in sim/scene/gltf_source.cpp).
#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    occsim::fuzz::gltfInput(data, size);
    return 0;
}
