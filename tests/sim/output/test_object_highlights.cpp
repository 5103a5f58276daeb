// The objects report.md points at (sim/output/object_highlights.h): frame lists as ranges, the
// note on the repetitions not recorded, and the section's two tables.
#include <gtest/gtest.h>

#include <string>

#include "sim/output/object_highlights.h"

namespace occsim {
namespace {

TEST(WhyWording, FramesAreListedAsRanges) {
    EXPECT_EQ(frameRanges({}), "");
    EXPECT_EQ(frameRanges({7}), "7");
    EXPECT_EQ(frameRanges({3, 4, 5, 9, 12, 13, 14}), "3-5, 9, 12-14");
}

TEST(ObjectHighlights, TheRepetitionsNotRecordedAreNamedWithWhatTheyMissed) {
    EXPECT_EQ(laterRepetitionsNote(1, 5), "");
    EXPECT_EQ(laterRepetitionsNote(2, 0), "repetition 2, not recorded, missed none");
    EXPECT_EQ(laterRepetitionsNote(4, 7),
              "repetitions 2-4, not recorded, missed 7 more (objects × frames)");
}

TEST(ObjectHighlights, TheSectionListsEachObjectDrawnWhileHiddenAndEachMissOrSaysNone) {
    ObjectHighlights h;
    h.overdrawn_per_config = 5;
    EXPECT_NE(objectHighlightsMarkdown(h).find("per configuration:\n\nnone.\n\n**Missed**"),
              std::string::npos)
        << objectHighlightsMarkdown(h);

    h.repetitions = 3;
    h.overdrawn.push_back(OverdrawnObject{"chc", 17, "crate|2", 1200, 9, 4, 30});
    h.missed.push_back(MissedObject{"masked", 4, "wall", {3, 4, 5, 9}, 812});
    h.later_misses.push_back(LaterMisses{"masked", 6});
    const std::string md = objectHighlightsMarkdown(h);
    // A name with a table's bar keeps the row whole.
    EXPECT_NE(md.find("| chc | 17 crate\\|2 | 1200 | 9 | 4 (from frame 30) |"), std::string::npos)
        << md;
    EXPECT_NE(md.find("| masked | 4 wall | 3-5, 9 | 812 |"), std::string::npos) << md;
    EXPECT_NE(md.find("in the first of the 3 repetitions"), std::string::npos) << md;
    EXPECT_NE(md.find("- masked: repetitions 2-3, not recorded, missed 6 more"), std::string::npos)
        << md;
}

}  // namespace
}  // namespace occsim
