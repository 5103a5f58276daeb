// File names made from labels (sim/output/atomic_file.h): one path component, readable where the
// label allows (a culler's '+' kept), and distinct where two labels differ only in what was
// replaced.
#include <gtest/gtest.h>

#include <string>

#include "sim/output/atomic_file.h"

namespace occsim {
namespace {

TEST(SafeFileName, KeepsCullerNamesReadable) {
    EXPECT_EQ(safeFileName("statistical+"), "statistical+");
    EXPECT_EQ(safeFileName("chc++"), "chc++");
    EXPECT_EQ(safeFileName("ideal-box"), "ideal-box");
    EXPECT_EQ(safeFileName("v1.2_x"), "v1.2_x");
}

TEST(SafeFileName, MakesAnyLabelOnePathComponentWithoutHiddenFiles) {
    EXPECT_EQ(safeFileName("chc threshold_pixels=4"), "chc_threshold_pixels_4");
    EXPECT_EQ(safeFileName("a/b"), "a_b");
    EXPECT_EQ(safeFileName(".."), "_.");
    EXPECT_EQ(safeFileName(".hidden"), "_hidden");
    EXPECT_EQ(safeFileName(""), "_");
    EXPECT_EQ(safeFileName("\xC3\xA4"), "__");  // ä
}

TEST(DistinctFileName, AddsAHashOnlyWhereTheLabelChanged) {
    EXPECT_EQ(distinctFileName("statistical+"), "statistical+");
    EXPECT_NE(distinctFileName("a b"), distinctFileName("a/b"));
    EXPECT_NE(distinctFileName("\xC3\xA4"), distinctFileName("\xC3\xB6"));  // ä, ö
    EXPECT_EQ(distinctFileName("a b").rfind("a_b-", 0), 0u) << distinctFileName("a b");
}

}  // namespace
}  // namespace occsim
