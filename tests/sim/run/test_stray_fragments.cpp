// Stray fragments (sim/run/stray_fragments.h): a ground-truth pixel nearer than any point of its
// object can be is marked stray; nothing else is. No GL: the marking alone (ground truth on real
// frames: test_ground_truth.cpp).
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "sim/run/stray_fragments.h"

namespace occsim {
namespace {

// The marks are the frame's own: a second frame's call replaces the first's, and an ID beyond
// the objects given (a frame's IDs against last frame's bounds) is never stray.
TEST(StrayFragments, EachFrameIsMarkedAfreshAndAnUnknownIdIsNeverStray) {
    std::vector<uint8_t> stray;
    EXPECT_EQ(markStrayFragments(std::vector<uint32_t>{1, 1}, std::vector<uint32_t>{900, 900},
                                 std::vector<uint32_t>{100}, stray),
              2);
    EXPECT_EQ(
        markStrayFragments(std::vector<uint32_t>{1, 3, 0}, std::vector<uint32_t>{50, 900, 900},
                           std::vector<uint32_t>{100}, stray),
        0);
    EXPECT_EQ(stray, (std::vector<uint8_t>{0, 0, 0}));
}

TEST(StrayFragments, BuffersOfDifferentSizesAreRefused) {
    std::vector<uint8_t> stray;
    EXPECT_THROW(markStrayFragments(std::vector<uint32_t>{1, 1}, std::vector<uint32_t>{1},
                                    std::vector<uint32_t>{100}, stray),
                 std::invalid_argument);
}

TEST(StrayFragments, OnlyAFragmentNearerThanItsObjectsBoundIsStray) {
    //                                  bg  at bound  nearer  object 2 far
    const std::vector<uint32_t> ids = {0, 1, 1, 2};
    const std::vector<uint32_t> ranks = {99999, 500, 501, 10};
    const std::vector<uint32_t> nearest_rank = {500, 400};
    std::vector<uint8_t> stray;
    EXPECT_EQ(markStrayFragments(ids, ranks, nearest_rank, stray), 1);
    EXPECT_EQ(stray, (std::vector<uint8_t>{0, 0, 1, 0}));
}

}  // namespace
}  // namespace occsim
