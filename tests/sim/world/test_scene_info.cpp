// What `occsim info` says of a scenario (sim/world/scene_info.h): its objects, triangles, movers
// and tree.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "sim/scenario/scenario.h"
#include "sim/world/scene_info.h"

namespace occsim {
namespace {

const std::filesystem::path kSmall =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json";

TEST(Simulation, DescribeReportsObjectsTrianglesMoversAndTree) {
    std::vector<std::string> warnings;
    const std::string text = describeScenario(parseScenarioFile(kSmall), warnings);
    EXPECT_NE(text.find("objects       300"), std::string::npos) << text;
    EXPECT_NE(text.find("movers        90"), std::string::npos) << text;
    EXPECT_NE(text.find("bsp "), std::string::npos) << text;
    EXPECT_TRUE(warnings.empty());
}

}  // namespace
}  // namespace occsim
