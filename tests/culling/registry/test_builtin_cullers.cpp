// The built-in cullers' registry rows (culling/registry/builtin_cullers.cpp): their traits, their
// options' checks and their factories.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <typeindex>
#include <typeinfo>
#include <vector>

#include "culling/cullers/async_culler.h"
#include "culling/cullers/basic_cullers.h"
#include "culling/cullers/chc_culler.h"
#include "culling/cullers/chcpp_culler.h"
#include "culling/cullers/conditional_culler.h"
#include "culling/cullers/gpu_driven_culler.h"
#include "culling/cullers/hzb_culler.h"
#include "culling/cullers/masked_culler.h"
#include "culling/cullers/statistical_culler.h"
#include "culling_fixtures.h"
#include "occsim/culling/registry/registry.h"

namespace occsim {
namespace {

// The class each built-in row's factory makes (Culler::name() went with plugin ABI 5: nothing
// but these tests read it).
std::type_index builtinCullerType(const std::string& name) {
    static const std::map<std::string, std::type_index> types = {
        {"vfc", typeid(VfcCuller)},
        {"stop-and-wait", typeid(StopAndWaitCuller)},
        {"ideal", typeid(IdealCuller)},
        {"ideal-box", typeid(IdealBoxCuller)},
        {"chc", typeid(ChcCuller)},
        {"chc++", typeid(ChcppCuller)},
        {"async", typeid(AsyncCuller)},
        {"conditional", typeid(ConditionalCuller)},
        {"hzb", typeid(GpuDrivenCuller)},  // `read_back=true`: HzbCuller
        {"raster", typeid(GpuDrivenCuller)},
        {"masked", typeid(MaskedCuller)},
        {"statistical", typeid(StatisticalCuller)},
        {"statistical+", typeid(StatisticalCuller)},
    };
    const auto found = types.find(name);
    if (found == types.end()) {
        ADD_FAILURE() << name << ": a built-in culler this test does not know; add its class";
        return typeid(void);
    }
    return found->second;
}

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
        const CullerRow& a = *findCuller(name);
        EXPECT_EQ(checkOptionValues(a, OptionValues(a.options)), "") << name;
    }
    EXPECT_EQ(OptionValues(findCuller("chc++")->options).count("batch_size"),
              ChcppOptions{}.batch_size);
    EXPECT_EQ(ChcppOptions{}.batch_size, 50u);
    EXPECT_EQ(AsyncOptions{}.retest_interval_frames, 5u);

    const auto rejects = [](const char* culler, const char* key, double value) {
        const CullerRow& a = *findCuller(culler);
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
    const std::vector<std::string>& names = cullerNames();
    for (const char* name : {"chc", "chc++", "async"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
        const std::unique_ptr<Culler> culler = testing::cullerNamed(name, CullerOptions{});
        ASSERT_NE(culler, nullptr) << name;
        EXPECT_EQ(std::type_index(typeid(*culler)), builtinCullerType(name)) << name;
    }
}

// What each algorithm is comes from its registration, and every built-in row's factory makes the
// culler of that name.
TEST(AlgorithmRegistry, StatesWhatEachAlgorithmIs) {
    for (const CullerRow* a_row : cullerRows()) {
        const CullerRow& a = *a_row;
        const std::unique_ptr<Culler> culler = makeCuller(a, CullerOptions{});
        ASSERT_NE(culler, nullptr) << a.name;
        if (a.source.empty()) {
            EXPECT_EQ(std::type_index(typeid(*culler)), builtinCullerType(a.name)) << a.name;
        }
        EXPECT_EQ(findCuller(a.name), &a);
        EXPECT_FALSE(a.oracle && a.issues_queries) << a.name;
    }
    EXPECT_EQ(findCuller("nope"), nullptr);
    EXPECT_TRUE(findCuller("vfc")->speedup_reference);
    EXPECT_EQ(speedupReference().name, "vfc");
    EXPECT_TRUE(findCuller("ideal")->oracle);
    EXPECT_FALSE(findCuller("async")->conservative);
    for (const char* name : {"stop-and-wait", "statistical", "statistical+", "chc", "chc++"}) {
        EXPECT_TRUE(findCuller(name)->conservative) << name;
        EXPECT_TRUE(findCuller(name)->issues_queries) << name;
    }
}

}  // namespace
}  // namespace occsim
