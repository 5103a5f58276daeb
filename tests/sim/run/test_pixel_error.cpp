// Error against tie, pixel by pixel (sim/run/pixel_error.h): no GL, the classification alone.
#include <gtest/gtest.h>

#include <vector>

#include "sim/run/pixel_error.h"

namespace occsim {
namespace {

constexpr uint32_t kBackground = 0;

TEST(PixelError, TheSameIdIsNoDifferenceWhateverTheDepth) {
    EXPECT_EQ(classifyPixel(3, 1000, 3, 1000), PixelDifference::Same);
    EXPECT_EQ(classifyPixel(kBackground, 0, kBackground, 0), PixelDifference::Same);
}

TEST(PixelError, AnotherObjectAtTheSameDepthWithinOneStepIsATie) {
    EXPECT_EQ(classifyPixel(3, 1000, 4, 1000), PixelDifference::Tie);
    EXPECT_EQ(classifyPixel(3, 1000, 4, 1000 - kDepthTieSteps), PixelDifference::Tie);
    EXPECT_EQ(classifyPixel(3, 1000, 4, 1000 + kDepthTieSteps), PixelDifference::Tie);
}

TEST(PixelError, GroundTruthNearerByMoreThanTheToleranceIsAnError) {
    EXPECT_EQ(classifyPixel(3, 1000, 4, 1000 - kDepthTieSteps - 1), PixelDifference::Error);
    EXPECT_EQ(classifyPixel(3, 0x3F000000u, 4, 0x3E000000u), PixelDifference::Error);
}

TEST(PixelError, BackgroundIsInfinitelyFarAndNeverTiesWithAnObject) {
    // An object's fragment at the far plane stores the background's rank; still no tie.
    EXPECT_EQ(classifyPixel(3, 0, kBackground, 0), PixelDifference::Error);
    EXPECT_EQ(classifyPixel(3, 1000, kBackground, 0), PixelDifference::Error);
}

TEST(PixelError, ACulledFrameNearerThanGroundTruthIsAnErrorNotATie) {
    // No subset of the same fragments can do this; if a culled frame does, it is wrong.
    EXPECT_EQ(classifyPixel(kBackground, 0, 4, 1000), PixelDifference::Error);
    EXPECT_EQ(classifyPixel(3, 1000, 4, 5000), PixelDifference::Error);
}

TEST(PixelError, AFrameCountsErrorsAndTiesApartAndMarksEachPixel) {
    //                                 same  tie   error  error(bg)  same(bg)  tie
    const std::vector<uint32_t> truth_ids = {1, 2, 3, 4, 0, 5};
    const std::vector<uint32_t> truth_depth = {900, 800, 700, 600, 0, 50};
    const std::vector<uint32_t> culled_ids = {1, 6, 7, 0, 0, 8};
    const std::vector<uint32_t> culled_depth = {900, 800, 100, 0, 0, 51};
    std::vector<uint8_t> marks;
    const PixelCounts counts =
        comparePixels(truth_ids, truth_depth, culled_ids, culled_depth, {}, &marks);
    EXPECT_EQ(counts.error, 2);
    EXPECT_EQ(counts.tie, 2);
    const std::vector<PixelDifference> expected = {PixelDifference::Same,  PixelDifference::Tie,
                                                   PixelDifference::Error, PixelDifference::Error,
                                                   PixelDifference::Same,  PixelDifference::Tie};
    ASSERT_EQ(marks.size(), expected.size());
    for (size_t i = 0; i < marks.size(); ++i)
        EXPECT_EQ(static_cast<PixelDifference>(marks[i]), expected[i]) << i;
    const PixelCounts unmarked = comparePixels(truth_ids, truth_depth, culled_ids, culled_depth);
    EXPECT_EQ(unmarked.error, counts.error);
    EXPECT_EQ(unmarked.tie, counts.tie);
}

TEST(PixelError, AMissingStrayFragmentIsStrayAndEveryOtherPixelKeepsItsClass) {
    //                                 stray  error  stray but same  tie
    const std::vector<uint32_t> truth_ids = {1, 2, 3, 4};
    const std::vector<uint32_t> truth_depth = {900, 700, 600, 50};
    const std::vector<uint8_t> truth_stray = {1, 0, 1, 0};
    const std::vector<uint32_t> culled_ids = {5, 0, 3, 8};
    const std::vector<uint32_t> culled_depth = {100, 0, 600, 51};
    std::vector<uint8_t> marks;
    const PixelCounts counts =
        comparePixels(truth_ids, truth_depth, culled_ids, culled_depth, truth_stray, &marks);
    EXPECT_EQ(counts.stray, 1);
    EXPECT_EQ(counts.error, 1);
    EXPECT_EQ(counts.tie, 1);
    const std::vector<PixelDifference> expected = {PixelDifference::Stray, PixelDifference::Error,
                                                   PixelDifference::Same, PixelDifference::Tie};
    for (size_t i = 0; i < marks.size(); ++i)
        EXPECT_EQ(static_cast<PixelDifference>(marks[i]), expected[i]) << i;
}

TEST(PixelError, BuffersOfDifferentSizesAreRefused) {
    const std::vector<uint32_t> four(4, 0), three(3, 0);
    EXPECT_THROW(comparePixels(four, four, four, three), std::invalid_argument);
    const std::vector<uint8_t> stray(3, 0);
    EXPECT_THROW(comparePixels(four, four, four, four, stray), std::invalid_argument);
}

// The frame's pixels per object: ground truth's own (not stray), and each error or tie pixel
// on the object ground truth shows there; an error over background on the object drawn there.
TEST(PixelError, ErrorAndTiePixelsGoToTheObjectGroundTruthShowsThere) {
    //                                 same  error  tie  stray  error over bg  bg
    const std::vector<uint32_t> truth_ids = {1, 2, 2, 1, 0, 0};
    const std::vector<uint32_t> truth_depth = {50, 60, 70, 80, 0, 0};
    const std::vector<uint32_t> culled_ids = {1, 0, 3, 0, 3, 0};
    const std::vector<uint32_t> culled_depth = {50, 0, 70, 0, 40, 0};
    const std::vector<uint8_t> truth_stray = {0, 0, 0, 1, 0, 0};
    std::vector<uint8_t> marks;
    const PixelCounts counts =
        comparePixels(truth_ids, truth_depth, culled_ids, culled_depth, truth_stray, &marks);
    std::vector<ObjectPixels> per_object;
    attributePixels(truth_ids, truth_stray, culled_ids, marks, 3, per_object);
    ASSERT_EQ(per_object.size(), 3u);
    EXPECT_EQ(per_object[0].truth, 1u) << "its stray fragment is not its own";
    EXPECT_EQ(per_object[0].error, 0u);
    EXPECT_EQ(per_object[1].truth, 2u);
    EXPECT_EQ(per_object[1].error, 1u);
    EXPECT_EQ(per_object[1].tie, 1u);
    EXPECT_EQ(per_object[2].truth, 0u);
    EXPECT_EQ(per_object[2].error, 1u) << "drawn over background: nearer than ground truth";
    int64_t errors = 0, ties = 0;
    for (const ObjectPixels& p : per_object) {
        errors += p.error;
        ties += p.tie;
    }
    EXPECT_EQ(errors, counts.error);
    EXPECT_EQ(ties, counts.tie);
    EXPECT_THROW(
        attributePixels(truth_ids, truth_stray, culled_ids, std::vector<uint8_t>(2), 3, per_object),
        std::invalid_argument);
}

}  // namespace
}  // namespace occsim
