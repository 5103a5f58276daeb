// The strict reader's helpers: the edit distance behind its suggestions, JSON pointers, numbers.
#include <gtest/gtest.h>

#include <string>

#include "scenario_fixtures.h"
#include "sim/scenario/option_json.h"

namespace occsim {
namespace {

using namespace fixtures;

TEST(JsonReader, EditDistanceCountsTranspositionsAsOneEdit) {
    EXPECT_EQ(editDistance("frmaes", "frames"), 1u);
    EXPECT_EQ(editDistance("", "abc"), 3u);
    EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
    EXPECT_EQ(closestMatch("nera", {"near", "far"}), std::optional<std::string>("near"));
    EXPECT_EQ(closestMatch("zzzzzz", {"near", "far"}), std::nullopt);
}

TEST(JsonReader, PointersEscapeTildeAndSlash) {
    EXPECT_EQ(appendJsonPointer("/a", "b/c~d"), "/a/b~1c~0d");
}

TEST(JsonReader, NonFiniteNumberBuiltInCodeIsRejected) {
    const json value = std::numeric_limits<double>::infinity();
    const JsonValueReader reader(value, "/x", "code");
    EXPECT_THROW(reader.asNumber(), ScenarioError);
}

}  // namespace
}  // namespace occsim
