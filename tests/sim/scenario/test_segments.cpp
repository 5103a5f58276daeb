// Segments as written: a scenario's "segments" and `--segments`, placed on a run's frames, and
// the checks of an "expect" block scoped to a segment. Every bad input is one message naming the
// file and JSON pointer (or the flag and the item) and what was expected.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/scenario/scenario.h"

namespace occsim {
namespace {

using nlohmann::json;

const char* const kFile = "scenarios/segments.json";

// 150 frames at 30 a second: 0 to 5 s.
json scenarioWith(const json& segments) {
    json s = json::parse(R"({
        "format_version": 1,
        "frames": 150,
        "dt": 0.0333333,
        "camera": {"keyframes": [{"time": 0, "position": [0, 2, 10], "target": [0, 2, 0]}]},
        "scene": {"sources": [{"type": "teapots", "count": 10}]}
    })");
    s["segments"] = segments;
    return s;
}

std::string errorFor(const json& scenario) {
    try {
        parseScenarioText(scenario.dump(2), kFile);
    } catch (const ScenarioError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a ScenarioError for:\n" << scenario.dump(2);
    return {};
}

void expectError(const json& scenario, const std::string& pointer, const std::string& fragment) {
    const std::string message = errorFor(scenario);
    const std::string prefix = std::string(kFile) + ": " + pointer + ": ";
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message << "\nexpected prefix: " << prefix;
    EXPECT_NE(message.find(fragment), std::string::npos) << message << "\nexpected: " << fragment;
}

TEST(Segments, SecondsAndFramesPlaceOnTheSameFramesWithToExclusive) {
    const Scenario s = parseScenarioText(
        scenarioWith({{{"name", "corner"}, {"from", 4.0}, {"to", 4.6}},
                      {{"name", "truck"}, {"from_frame", 120}, {"to_frame", 138}}})
            .dump(),
        kFile);
    ASSERT_EQ(s.segments.size(), 2u);
    const Segment corner = placeSegment(s.segments[0], s.frames, s.dt_s);
    const Segment truck = placeSegment(s.segments[1], s.frames, s.dt_s);
    // Frame 120 is at 3.999996 s with this dt: within a thousandth of a frame, so it is 4.0 s's.
    EXPECT_EQ(corner.first_frame, 120u);
    EXPECT_EQ(corner.end_frame, 138u);
    EXPECT_EQ(truck.first_frame, 120u);
    EXPECT_EQ(truck.end_frame, 138u);
    EXPECT_EQ(corner.frames(), 18u);
    EXPECT_TRUE(corner.contains(137));
    EXPECT_FALSE(corner.contains(138));
    EXPECT_EQ(corner.origin, "scenario");
}

TEST(Segments, ASegmentToTheEndOfTheRunFits) {
    const Scenario s =
        parseScenarioText(scenarioWith({{{"name", "all"}, {"from", 0}, {"to", 5}}}).dump(), kFile);
    const Segment all = placeSegment(s.segments[0], s.frames, s.dt_s);
    EXPECT_EQ(all.first_frame, 0u);
    EXPECT_EQ(all.end_frame, 150u);
}

TEST(Segments, EveryBadSegmentInAScenarioNamesItsPointer) {
    expectError(scenarioWith({{{"name", "late"}, {"from", 4.0}, {"to", 6.0}}}), "/segments/0/to",
                "(the end of the run: 150 frames, 0.0333333 s apart: 0 to ");
    expectError(scenarioWith({{{"name", "later"}, {"from", 5.5}, {"to", 6.0}}}), "/segments/0/from",
                "expected a time before the end of the run");
    expectError(scenarioWith({{{"name", "back"}, {"from", 4.6}, {"to", 4.0}}}), "/segments/0/to",
                "expected a time after from (4.6 s");
    expectError(scenarioWith({{{"name", "empty"}, {"from", 4.0}, {"to", 4.0}}}), "/segments/0/to",
                "expected a time after from");
    expectError(scenarioWith({{{"name", "thin"}, {"from", 4.001}, {"to", 4.002}}}),
                "/segments/0/to", "no frame lies in [4.001 s, 4.002 s)");
    expectError(scenarioWith({{{"name", "past"}, {"from_frame", 140}, {"to_frame", 151}}}),
                "/segments/0/to_frame", "expected a frame <= 150");
    expectError(scenarioWith({{{"name", "past"}, {"from_frame", 150}, {"to_frame", 151}}}),
                "/segments/0/from_frame", "expected a frame < 150");
    expectError(scenarioWith({{{"name", "back"}, {"from_frame", 20}, {"to_frame", 20}}}),
                "/segments/0/to_frame", "expected a frame after from_frame (20");
    expectError(scenarioWith({{{"name", ""}, {"from", 1}, {"to", 2}}}), "/segments/0/name",
                "expected a segment name of 1 to 64 letters");
    expectError(scenarioWith({{{"name", "a,b"}, {"from", 1}, {"to", 2}}}), "/segments/0/name",
                "expected a segment name");
    expectError(scenarioWith({{{"name", "a"}, {"from", 1}, {"to", 2}},
                              {{"name", "a"}, {"from", 2}, {"to", 3}}}),
                "/segments/1/name", "'a' already names the segment at /segments/0");
    expectError(scenarioWith({{{"name", "a"}, {"from", 1}, {"to_frame", 40}}}), "/segments/0",
                "not both");
    expectError(scenarioWith({{{"name", "a"}}}), "/segments/0",
                "expected from and to (seconds) or from_frame and to_frame (frames)");
    expectError(scenarioWith({{{"name", "a"}, {"from", 1}}}), "/segments/0/to",
                "missing required key 'to'");
    expectError(scenarioWith({{{"name", "a"}, {"from", -1}, {"to", 2}}}), "/segments/0/from",
                "expected a number >= 0");
    expectError(scenarioWith({{{"name", "a"}, {"from", 1}, {"to", 2}, {"too", 3}}}),
                "/segments/0/too", "unknown key 'too'");
    expectError(scenarioWith({{{"name", "a"}, {"from_frame", 1.5}, {"to_frame", 3}}}),
                "/segments/0/from_frame", "got 1.5");
    expectError(scenarioWith(json::object()), "/segments", "expected an array");
}

TEST(SegmentList, ParsesSecondsAndFramesAndKeepsTheOrder) {
    const std::vector<SegmentSpec> specs =
        parseSegmentList("corner=4.0:4.6,truck=f120:138,start=0:.5,f=f1:f3");
    ASSERT_EQ(specs.size(), 4u);
    EXPECT_EQ(specs[0].name, "corner");
    EXPECT_FALSE(specs[0].in_frames);
    EXPECT_DOUBLE_EQ(specs[0].from_s, 4.0);
    EXPECT_DOUBLE_EQ(specs[0].to_s, 4.6);
    EXPECT_EQ(specs[0].item, "corner=4.0:4.6");
    EXPECT_TRUE(specs[1].in_frames);
    EXPECT_EQ(specs[1].from_frame, 120u);
    EXPECT_EQ(specs[1].to_frame, 138u);
    EXPECT_DOUBLE_EQ(specs[2].to_s, 0.5);
    EXPECT_EQ(specs[3].name, "f");
    EXPECT_EQ(specs[3].to_frame, 3u);
    EXPECT_TRUE(specs[0].file.empty());
}

TEST(SegmentList, EveryMalformedItemIsNamedWithWhatWasExpected) {
    const struct {
        std::string text, fragment;
    } cases[] = {
        {"", "'': expected NAME=FROM:TO (seconds) or NAME=fFROM:TO (frames), got an empty item"},
        {"a=1:2,", "'': expected NAME=FROM:TO"},
        {"corner", "'corner': expected NAME=FROM:TO (seconds) or NAME=fFROM:TO (frames) (no '=')"},
        {"=1:2", "'=1:2': expected a segment name"},
        {"a b=1:2", "'a b=1:2': expected a segment name"},
        {"a=1", "'a=1': expected NAME=FROM:TO (seconds) or NAME=fFROM:TO (frames) (one ':'"},
        {"a=1:2:3", "(one ':' between FROM and TO)"},
        {"a=one:2",
         "'a=one:2': expected NAME=FROM:TO (seconds) or NAME=fFROM:TO (frames): seconds"},
        {"a=-1:2", "seconds are numbers from 0"},
        {"a=1:inf", "seconds are numbers from 0"},
        {"a=fx:2", "frames are whole numbers from 0"},
        {"a=f1.5:4", "frames are whole numbers from 0"},
        {"a=f99999999999:99999999999", "frames are whole numbers from 0"},
        {"a=2:1", "'a=2:1': expected TO after FROM (TO is exclusive), got 1 <= 2"},
        {"a=f5:5", "expected TO after FROM (TO is exclusive), got 5 <= 5"},
        {"a=1:2,a=3:4", "'a=3:4': 'a' is given twice"},
    };
    for (const auto& c : cases) {
        try {
            parseSegmentList(c.text);
            ADD_FAILURE() << "accepted: " << c.text;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos)
                << c.text << ": " << e.what();
        }
    }
}

TEST(SegmentList, ASegmentPastTheRunIsBadInputNamingTheFlagAndTheItem) {
    const std::vector<SegmentSpec> late = parseSegmentList("late=4.5:5.5");
    try {
        planSegments({}, 150, late, 150, 1.0 / 30.0);
        FAIL() << "a segment past the run was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(
            std::string(e.what()).rfind("--segments: 'late=4.5:5.5': expected a time <= 5 s", 0),
            0u)
            << e.what();
    }
    // The run is as long as it runs: --frames 60 ends it at 2 s.
    EXPECT_THROW(planSegments({}, 150, parseSegmentList("a=f50:61"), 60, 1.0 / 30.0), InputError);
    EXPECT_NO_THROW(planSegments({}, 150, parseSegmentList("a=f50:60"), 60, 1.0 / 30.0));
}

TEST(SegmentList, AFlagSegmentMayNotTakeAScenarioSegmentsName) {
    const Scenario s = parseScenarioText(
        scenarioWith({{{"name", "corner"}, {"from", 4.0}, {"to", 4.6}}}).dump(), kFile);
    try {
        planSegments(s.segments, s.frames, parseSegmentList("corner=1:2"), s.frames, s.dt_s);
        FAIL() << "a repeated name was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("'corner' already names a segment of the scenario "
                                             "(scenarios/segments.json: /segments/0)"),
                  std::string::npos)
            << e.what();
    }
}

TEST(SegmentList, AShorterRunCutsOrDropsTheScenariosSegmentsAndSaysSo) {
    const Scenario s =
        parseScenarioText(scenarioWith({{{"name", "early"}, {"from_frame", 0}, {"to_frame", 30}},
                                        {{"name", "across"}, {"from_frame", 20}, {"to_frame", 60}},
                                        {{"name", "late"}, {"from_frame", 100}, {"to_frame", 150}}})
                              .dump(),
                          kFile);
    const PlannedSegments plan = planSegments(s.segments, s.frames, {}, 40, s.dt_s);
    ASSERT_EQ(plan.segments.size(), 2u);
    EXPECT_EQ(plan.segments[0].end_frame, 30u);
    EXPECT_TRUE(plan.segments[0].note.empty());
    EXPECT_EQ(plan.segments[1].name, "across");
    EXPECT_EQ(plan.segments[1].end_frame, 40u);
    EXPECT_NE(plan.segments[1].note.find("cut to frame 39"), std::string::npos);
    ASSERT_EQ(plan.notes.size(), 2u);
    EXPECT_NE(plan.notes[0].find("'across' (frames 20 to 59) cut to frame 39"), std::string::npos)
        << plan.notes[0];
    EXPECT_NE(plan.notes[1].find("'late' (frames 100 to 149) lies past this run's 40 frames: "
                                 "left out"),
              std::string::npos)
        << plan.notes[1];
}

// ---- checks scoped to a segment ---------------------------------------------------------

json withExpect(const json& expect) {
    json s = scenarioWith({{{"name", "turn"}, {"from", 1.0}, {"to", 2.0}},
                           {{"name", "late"}, {"from_frame", 100}, {"to_frame", 150}}});
    s["expect"] = expect;
    return s;
}

TEST(SegmentExpectations, RatiosAndErrorChecksNameTheirSegment) {
    const Scenario s = parseScenarioText(withExpect(json::parse(R"({
        "algorithms": ["vfc", "async", "ideal"],
        "zero_error": ["vfc", {"algorithm": "async", "segment": "turn"}],
        "max_error_pixels": [{"algorithm": "async", "max": 500, "segment": "late"},
                             {"algorithm": "async", "max": 2000}],
        "ratios": [{"algorithm": "async", "reference": "ideal", "max": 1.1, "segment": "turn"}]
    })"))
                                             .dump(),
                                         kFile);
    const Expectations& e = *s.expect;
    EXPECT_EQ(e.zero_error, std::vector<std::string>{"vfc"});
    ASSERT_EQ(e.segment_errors.size(), 2u);
    EXPECT_EQ(e.segment_errors[0].algorithm, "async");
    EXPECT_EQ(e.segment_errors[0].segment, "turn");
    EXPECT_FALSE(e.segment_errors[0].max_pixels.has_value());
    EXPECT_EQ(e.segment_errors[1].segment, "late");
    EXPECT_EQ(e.segment_errors[1].max_pixels, 500);
    EXPECT_EQ(e.max_error_pixels.at("async"), 2000);
    ASSERT_EQ(e.ratios.size(), 1u);
    EXPECT_EQ(e.ratios[0].segment, "turn");
}

TEST(SegmentExpectations, AnUnknownSegmentOrOnePastExpectFramesIsAnError) {
    const struct {
        const char* expect;
        std::string pointer, fragment;
    } cases[] = {
        {R"({"algorithms": ["vfc", "ideal"],
             "ratios": [{"algorithm": "vfc", "reference": "ideal", "max": 1, "segment": "corner"}]})",
         "/expect/ratios/0/segment", "expected a segment named in /segments (turn, late)"},
        {R"({"algorithms": ["vfc", "ideal"], "frames": 120,
             "ratios": [{"algorithm": "vfc", "reference": "ideal", "max": 1, "segment": "late"}]})",
         "/expect/ratios/0/segment",
         "segment 'late' (frames 100 to 149) reaches past the 120 frames this run runs"},
        {R"({"algorithms": ["vfc", "ideal"], "frames": 120,
             "max_error_pixels": [{"algorithm": "vfc", "max": 0, "segment": "late"}]})",
         "/expect/max_error_pixels/0/segment", "reaches past the 120 frames"},
        {R"({"algorithms": ["vfc", "ideal"],
             "zero_error": [{"algorithm": "statistical", "segment": "turn"}]})",
         "/expect/zero_error/0/algorithm", "an algorithm listed in /expect/algorithms"},
        {R"({"algorithms": ["vfc", "ideal"], "zero_error": [{"algorithm": "vfc"}]})",
         "/expect/zero_error/0/segment", "missing required key 'segment'"},
        {R"({"algorithms": ["vfc", "ideal"], "zero_error": [3]})", "/expect/zero_error/0",
         "an algorithm's name or {\"algorithm\""},
        {R"({"algorithms": ["vfc", "ideal"],
             "max_error_pixels": [{"algorithm": "vfc", "max": 1}, {"algorithm": "vfc", "max": 2}]})",
         "/expect/max_error_pixels/1/algorithm", "'vfc' has a whole-run bound already"},
        {R"({"algorithms": ["vfc", "ideal"], "max_error_pixels": 3})", "/expect/max_error_pixels",
         "an object of bounds"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.expect);
        expectError(withExpect(json::parse(c.expect)), c.pointer, c.fragment);
    }
    json none = scenarioWith(json::array());
    none["expect"] = json::parse(R"({"algorithms": ["vfc", "ideal"],
        "ratios": [{"algorithm": "vfc", "reference": "ideal", "max": 1, "segment": "turn"}]})");
    expectError(none, "/expect/ratios/0/segment", "the scenario names none");
}

}  // namespace
}  // namespace occsim
