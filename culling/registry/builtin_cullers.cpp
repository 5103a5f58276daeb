// The built-in cullers, in the order tables list them. Each is registered by a function in its own
// file (cullers/), returning its row; adding a culler in the tree is that file and one line here.
#include "occsim/culling/registry/registry.h"

namespace occsim {

CullerRow vfcRegistration();              // cullers/basic_cullers.cpp
CullerRow stopAndWaitRegistration();      // cullers/basic_cullers.cpp
CullerRow statisticalRegistration();      // cullers/statistical_registration.cpp
CullerRow statisticalPlusRegistration();  // cullers/statistical_registration.cpp
CullerRow chcRegistration();              // cullers/chc_culler.cpp
CullerRow chcppRegistration();            // cullers/chcpp_culler.cpp
CullerRow asyncRegistration();            // cullers/async_culler.cpp
CullerRow conditionalRegistration();      // cullers/conditional_culler.cpp
CullerRow hzbRegistration();              // cullers/hzb_culler.cpp
CullerRow rasterRegistration();           // cullers/hzb_culler.cpp
CullerRow idealRegistration();            // cullers/basic_cullers.cpp
CullerRow idealBoxRegistration();         // cullers/basic_cullers.cpp
CullerRow maskedRegistration();           // cullers/masked_culler.cpp

void registerBuiltinCullers(CullerRegistry& registry) {
    for (CullerRow (*row)() :
         {vfcRegistration, stopAndWaitRegistration, statisticalRegistration,
          statisticalPlusRegistration, chcRegistration, chcppRegistration, asyncRegistration,
          conditionalRegistration, hzbRegistration, rasterRegistration, maskedRegistration,
          idealRegistration, idealBoxRegistration}) {
        registry.add(row());
    }
}

}  // namespace occsim
