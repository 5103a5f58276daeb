// The built-in cullers, in the order tables list them. Each is registered by a function in its own
// file (cullers/), returning its row; adding a culler in the tree is that file and one line here.
#include "occsim/culling/registry/registry.h"

namespace occsim {

AlgorithmTraits vfcRegistration();              // cullers/basic_cullers.cpp
AlgorithmTraits stopAndWaitRegistration();      // cullers/basic_cullers.cpp
AlgorithmTraits statisticalRegistration();      // cullers/statistical_registration.cpp
AlgorithmTraits statisticalPlusRegistration();  // cullers/statistical_registration.cpp
AlgorithmTraits chcRegistration();              // cullers/chc_culler.cpp
AlgorithmTraits chcppRegistration();            // cullers/chcpp_culler.cpp
AlgorithmTraits asyncRegistration();            // cullers/async_culler.cpp
AlgorithmTraits conditionalRegistration();      // cullers/conditional_culler.cpp
AlgorithmTraits hzbRegistration();              // cullers/hzb_culler.cpp
AlgorithmTraits idealRegistration();            // cullers/basic_cullers.cpp
AlgorithmTraits idealBoxRegistration();         // cullers/basic_cullers.cpp
AlgorithmTraits maskedRegistration();           // cullers/masked_culler.cpp

void registerBuiltinCullers(CullerRegistry& registry) {
    for (AlgorithmTraits (*row)() :
         {vfcRegistration, stopAndWaitRegistration, statisticalRegistration,
          statisticalPlusRegistration, chcRegistration, chcppRegistration, asyncRegistration,
          conditionalRegistration, hzbRegistration, maskedRegistration, idealRegistration,
          idealBoxRegistration}) {
        registry.add(row());
    }
}

}  // namespace occsim
