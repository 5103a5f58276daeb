// PLACEHOLDER while the generator is being written; replaced before the issue is resolved.
#include "sim/generators.h"

#include <stdexcept>

namespace occsim {

SourceOutput generateCity(const CitySpec&, uint64_t) {
    throw std::runtime_error("the city generator is not implemented yet");
}

}  // namespace occsim
