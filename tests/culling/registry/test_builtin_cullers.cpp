// The built-in cullers' registry rows (culling/registry/builtin_cullers.cpp): their traits, their
// options' checks and their factories.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "culling/cullers/async_culler.h"
#include "culling/cullers/chc_culler.h"
#include "culling/cullers/chcpp_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/registry/registry.h"

namespace occsim {
namespace {

using testing::buildTree;
using testing::gridBoxes;
using testing::inFrustum;
using testing::makeFrame;
using testing::makeView;
using testing::overview;
using testing::randomBoxes;
using testing::randomVisibility;

TEST(PeerCullerOptions, DefaultsAreValidAndOutOfRangeValuesAreRejectedWithAMessage) {
    for (const char* name : {"chc", "chc++", "async"}) {
        const AlgorithmTraits& a = *findAlgorithm(name);
        EXPECT_EQ(checkOptionValues(a, OptionValues(a.options)), "") << name;
    }
    EXPECT_EQ(OptionValues(findAlgorithm("chc++")->options).count("batch_size"),
              ChcppOptions{}.batch_size);
    EXPECT_EQ(ChcppOptions{}.batch_size, 50u);
    EXPECT_EQ(AsyncOptions{}.retest_interval_frames, 5u);

    const auto rejects = [](const char* culler, const char* key, double value) {
        const AlgorithmTraits& a = *findAlgorithm(culler);
        OptionValues v(a.options);
        v.set(key, value);
        const std::string why = checkOptionValues(a, v);
        EXPECT_EQ(why.rfind(key, 0), 0u) << culler << " " << key << ": " << why;
    };
    rejects("chc", "visible_frames_skip", 2000000);
    rejects("chc++", "batch_size", 0);
    rejects("chc++", "tight_bounds_depth", 7);
    rejects("chc++", "multiqueries", 0.5);
    rejects("async", "retest_interval_frames", 0);
}

TEST(PeerCullerOptions, TheFactoryKnowsTheThreeByName) {
    const std::vector<std::string>& names = algorithmNames();
    for (const char* name : {"chc", "chc++", "async"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
        const std::unique_ptr<Culler> culler = testing::cullerNamed(name, CullerOptions{});
        ASSERT_NE(culler, nullptr) << name;
        EXPECT_EQ(culler->name(), name);
    }
}

// What each algorithm is comes from its registration, and every registered culler reports the
// name it was registered under.
TEST(AlgorithmRegistry, StatesWhatEachAlgorithmIs) {
    for (const AlgorithmTraits* a_row : algorithms()) {
        const AlgorithmTraits& a = *a_row;
        EXPECT_EQ(makeCuller(a, CullerOptions{})->name(), a.name);
        EXPECT_EQ(findAlgorithm(a.name), &a);
        EXPECT_FALSE(a.oracle && a.issues_queries) << a.name;
    }
    EXPECT_EQ(findAlgorithm("nope"), nullptr);
    EXPECT_TRUE(findAlgorithm("vfc")->speedup_reference);
    EXPECT_EQ(speedupReference().name, "vfc");
    EXPECT_TRUE(findAlgorithm("ideal")->oracle);
    EXPECT_FALSE(findAlgorithm("async")->conservative);
    for (const char* name : {"stop-and-wait", "statistical", "statistical+", "chc", "chc++"}) {
        EXPECT_TRUE(findAlgorithm(name)->conservative) << name;
        EXPECT_TRUE(findAlgorithm(name)->issues_queries) << name;
    }
}

}  // namespace
}  // namespace occsim
