// A run's culler options (occsim/culling/registry/culler_options.h): values by culler name,
// defaults for a culler not named, and the first invalid value named with its culler.
#include <gtest/gtest.h>

#include <string>

#include "occsim/culling/registry/culler_options.h"
#include "occsim/culling/registry/registry.h"

namespace occsim {
namespace {

TEST(CullerOptions, ACullerNotNamedTakesItsDefaultsAndEditChangesOnlyTheOneNamed) {
    const CullerRow& chc = *findCuller("chc");
    const CullerRow& async = *findCuller("async");
    CullerOptions options;
    EXPECT_EQ(options.of(chc), OptionValues(chc.options));
    options.edit(async).set("retest_interval_frames", 3);
    EXPECT_EQ(options.of(async).count("retest_interval_frames"), 3u);
    EXPECT_EQ(options.of(chc), OptionValues(chc.options));
    std::string error;
    EXPECT_TRUE(options.isValid(&error)) << error;
}

TEST(CullerOptions, TheFirstInvalidValueIsNamedWithItsCuller) {
    CullerOptions options;
    options.edit(*findCuller("async")).set("retest_interval_frames", 0);
    std::string error;
    EXPECT_FALSE(options.isValid(&error));
    EXPECT_EQ(error.rfind("async: retest_interval_frames: expected an integer", 0), 0u) << error;
    CullerOptions bad_costs;
    bad_costs.cost_model.triangle_ms = -1.0;
    EXPECT_FALSE(bad_costs.isValid(&error));
    EXPECT_NE(error.find("triangle_ms"), std::string::npos) << error;
}

}  // namespace
}  // namespace occsim
