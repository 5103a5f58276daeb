// PLACEHOLDER while the generator is being written; replaced before the issue is resolved.
#include "sim/generators.h"

#include <stdexcept>

namespace occsim {

SourceOutput generatePlant(const PlantSpec&, uint64_t) {
    throw std::runtime_error("the plant generator is not implemented yet");
}

}  // namespace occsim
