// The wording of `occsim why` without a run (sim/record/why.h): each kind of reason in words, with
// the query's frame and what ground truth saw. Why on recorded runs: tests/system/test_why.cpp.
#include <gtest/gtest.h>

#include <string>

#include "objects_fixtures.h"
#include "sim/record/why.h"

namespace occsim::testing {
namespace {

RecordedDecision decision(DecisionKind kind, uint32_t frame, bool drawn, uint32_t truth) {
    RecordedDecision d;
    d.frame = frame;
    d.drawn = drawn;
    d.why.kind = kind;
    d.truth_pixels = truth;
    return d;
}

TEST(WhyWording, EachReasonIsSaidInWordsWithTheQueryFrameAndGroundTruth) {
    RecordedDecision hid = decision(DecisionKind::CulledOnQuery, 178, false, 412);
    hid.why.query_frame = 176;
    hid.error_pixels = 300;
    EXPECT_EQ(describeDecision(hid),
              "not drawn: the query issued at frame 176 (2 frames before) answered occluded (0 "
              "samples); ground truth sees 412 px (missed: 300 error pixels)");

    RecordedDecision stats = decision(DecisionKind::DrawnOnStatistics, 30, true, 0);
    stats.why.query_frame = 12;
    stats.why.count = 3;
    stats.why.history = 4;
    stats.why.interval = 1.25f;
    stats.why.next_query = 1.65f;
    EXPECT_EQ(describeDecision(stats),
              "drawn: no query: its last query, issued at frame 12 (18 frames before), found it "
              "visible (3 of its last 4 answers visible); the decay curve gives 1.25 s, so it is "
              "queried again after 1.65 s; ground truth sees 0 px (drawn while hidden)");

    RecordedDecision pyramid = decision(DecisionKind::CulledOnPyramid, 5, false, 0);
    pyramid.why.phase = 2;
    pyramid.why.level = 3;
    EXPECT_EQ(describeDecision(pyramid),
              "not drawn: the depth pyramid hides it (phase 2, level 3); ground truth sees 0 px");

    RecordedDecision same = decision(DecisionKind::DrawnOnQuery, 9, true, 40);
    same.why.query_frame = 9;
    same.why.samples = 1;
    same.why.flags = kDecisionWaited;
    EXPECT_EQ(describeDecision(same),
              "drawn: the query issued this frame answered visible (1 sample, waited for); "
              "ground truth sees 40 px");

    // A light view's decision speaks of the shadow the caster throws on what the camera sees.
    RecordedDecision caster = decision(DecisionKind::CulledOnQuery, 7, false, 25);
    caster.why.query_frame = 7;
    caster.error_pixels = 25;
    EXPECT_EQ(describeDecision(caster, RecordedView::Light),
              "not drawn: the query issued this frame answered occluded (0 samples); ground "
              "truth shadows 25 visible px through it (missed: 25 shadow pixels left lit)");
    EXPECT_EQ(
        describeDecision(decision(DecisionKind::DrawnNoTest, 7, true, 0), RecordedView::Light),
        "drawn: with no test; ground truth shadows 0 visible px through it (drawn while its "
        "shadow falls on nothing visible)");

    RecordedDecision skipped = decision(DecisionKind::DrawnConditional, 4, false, 0);
    skipped.why.query_frame = 4;
    EXPECT_NE(describeDecision(skipped).find("the device skipped it"), std::string::npos);
    // Every kind has words of its own.
    for (uint32_t k = 0; k < kDecisionKinds; ++k) {
        const std::string s = describeDecision(decision(static_cast<DecisionKind>(k), 1, false, 0));
        EXPECT_GT(s.size(), std::string("not drawn: ; ground truth sees 0 px").size() + 8) << k;
    }
}

}  // namespace
}  // namespace occsim::testing
