// The registry (occsim/culling/registry/registry.h): what a culler needs of the device, checked
// before any work.
#include <gtest/gtest.h>

#include "occsim/culling/registry/registry.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim {
namespace {

TEST(RequireDeviceFeatures, RefusesTheConditionalCullerOnADeviceWithoutItInOneLine) {
    const CullerRow& t = *findCuller("conditional");
    ScriptedQueryDevice device;
    EXPECT_NO_THROW(requireDeviceFeatures(t, device.features()));
    device.offerConditionalRendering(false);
    try {
        requireDeviceFeatures(t, device.features());
        FAIL() << "accepted a device without conditional rendering";
    } catch (const RegistryError& e) {
        EXPECT_STREQ(e.what(),
                     "culler 'conditional' needs conditional rendering, which this device does "
                     "not offer");
    }
    EXPECT_NO_THROW(requireDeviceFeatures(*findCuller("vfc"), device.features()));
}

}  // namespace
}  // namespace occsim
