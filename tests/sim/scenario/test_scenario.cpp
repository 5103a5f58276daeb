// The strict scenario parser: every class of bad input fails with the file name and the exact JSON
// pointer of the offending value; a minimal file gets the documented defaults; the examples in
// docs/scenario-format.md parse.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "culling/cullers/statistical_culler.h"
#include "occsim/culling/registry/registry.h"
#include "sim/scenario/json_reader.h"
#include "sim/scenario/number_text.h"
#include "sim/scenario/option_json.h"
#include "sim/scenario/scenario.h"

namespace occsim {
namespace {

using nlohmann::json;

const char* const kFile = "scenarios/bad-input.json";

// The smallest scenario the format accepts.
json minimalScenario() {
    return json::parse(R"({
        "format_version": 1,
        "camera": {"keyframes": [{"time": 0, "position": [0, 2, 10], "target": [0, 2, 0]}]},
        "scene": {"sources": [{"type": "teapots"}]}
    })");
}

// Parses `text` and returns the error message; fails the test when parsing succeeds.
std::string errorForText(const std::string& text) {
    try {
        parseScenarioText(text, kFile);
    } catch (const ScenarioError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a ScenarioError for:\n" << text;
    return {};
}

std::string errorFor(const json& scenario) { return errorForText(scenario.dump(2)); }

// The message must be "<file>: <pointer>: ..." (just "<file>: ..." for errors about the whole
// file, pointer "") and contain `fragment`.
// A culler's option values as the scenario gave them (or their defaults).
OptionValues optionsOf(const Scenario& s, const char* culler) {
    return s.culler.of(*findCuller(culler));
}

StatisticalOptions statisticalOf(const Scenario& s, const char* culler = "statistical") {
    return statisticalOptionTable().read(optionsOf(s, culler));
}

void expectError(const std::string& message, const std::string& pointer,
                 const std::string& fragment) {
    const std::string prefix = std::string(kFile) + ": " + (pointer.empty() ? "" : pointer + ": ");
    EXPECT_EQ(message.rfind(prefix, 0), 0u)
        << "message: " << message << "\nexpected prefix: " << prefix;
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "message: " << message << "\nexpected to contain: " << fragment;
}

void expectError(const json& scenario, const std::string& pointer, const std::string& fragment) {
    expectError(errorFor(scenario), pointer, fragment);
}

std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The contents of every fenced block that opens with exactly "```json".
std::vector<std::string> jsonBlocks(const std::string& markdown) {
    std::vector<std::string> blocks;
    std::istringstream lines(markdown);
    std::string line;
    std::string block;
    bool inside = false;
    while (std::getline(lines, line)) {
        if (!inside && line == "```json") {
            inside = true;
            block.clear();
        } else if (inside && line.rfind("```", 0) == 0) {
            inside = false;
            blocks.push_back(block);
        } else if (inside) {
            block += line + "\n";
        }
    }
    return blocks;
}

// --- Files and syntax ----------------------------------------------------------------------

TEST(ScenarioFile, MissingFileSaysItCannotBeOpened) {
    const std::filesystem::path missing = "/nonexistent-dir/no-such-scenario.json";
    try {
        parseScenarioFile(missing);
        FAIL() << "expected a ScenarioError";
    } catch (const ScenarioError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(missing.string() + ": cannot open file: ", 0), 0u) << message;
        EXPECT_NE(message.find("No such file"), std::string::npos) << message;
    }
}

TEST(ScenarioFile, ReadsAFileFromDiskAndNamesItAfterTheStem) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("occsim-test-scenario-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = dir / "occsim-test-scenario-stem.json";
    std::ofstream(path) << minimalScenario().dump();
    const Scenario s = parseScenarioFile(path);
    std::filesystem::remove(path);
    EXPECT_EQ(s.file, path);
    EXPECT_EQ(s.name, "occsim-test-scenario-stem");
}

TEST(ScenarioSyntax, InvalidJsonReportsLineAndColumn) {
    const std::string text = "{\n  \"format_version\": 1,\n  \"frames\": 30x\n}\n";
    const std::string message = errorForText(text);
    expectError(message, "", "invalid JSON at line 3, column 15: ");
}

TEST(ScenarioSyntax, TrailingCommaIsInvalidJson) {
    const std::string text = "{\n  \"format_version\": 1,\n}";
    expectError(errorForText(text), "", "invalid JSON at line 3, column 1: ");
}

TEST(ScenarioSyntax, DuplicateKeyIsRejected) {
    const std::string text = R"({"format_version": 1, "camera": {"near": 1, "near": 2}})";
    expectError(errorForText(text), "/camera/near", "duplicate key 'near'");
}

TEST(ScenarioSyntax, NumberOverflowingToInfinityIsRejected) {
    json scenario = minimalScenario();
    std::string text = scenario.dump();
    text.insert(1, "\"dt\": 1e999, ");
    expectError(errorForText(text), "/dt", "expected a finite number, got 1e999");
}

TEST(ScenarioSyntax, NumberOverflowingToInfinityReportsWhereTheNumberStarts) {
    const std::string text = "{\n  \"format_version\": 1,\n  \"dt\": 2e400\n}";
    expectError(errorForText(text), "/dt",
                "got 2e400, which overflows a double (at line 3, column 9)");
}

TEST(ScenarioSyntax, NumberOverflowingInsideAnArrayNamesTheElement) {
    const std::string text = R"({"format_version": 1,
        "camera": {"keyframes": [{"time": 0, "position": [0, -1e400, 0]}]}})";
    expectError(errorForText(text), "/camera/keyframes/0/position/1", "1e400");
}

// Finite as a double but infinite as the float the world and the GPU hold: refused at the
// element, for the camera and for objects alike.
TEST(ScenarioSyntax, CoordinatesBeyondFloatRangeAreRefusedAtTheElement) {
    json camera = minimalScenario();
    camera["camera"]["keyframes"][0]["position"] = {0, 1e39, 0};
    expectError(errorFor(camera), "/camera/keyframes/0/position/1",
                "expected a coordinate that fits a 32-bit float (|x| < 3.4e38), got 1e");
    json orbit = minimalScenario();
    orbit["camera"] =
        json::parse(R"({"orbit": {"center": [-1e39, 0, 0], "radius": 5, "height": 2}})");
    expectError(errorFor(orbit), "/camera/orbit/center/0", "fits a 32-bit float");
    json gltf = minimalScenario();
    gltf["scene"]["sources"] =
        json::parse(R"([{"type": "gltf", "path": ")" + std::string(OCCSIM_SOURCE_DIR) +
                    R"(/scenarios/assets/Box/box.gltf", "offset": [0, 0, 1e39]}])");
    expectError(errorFor(gltf), "/scene/sources/0/offset/2", "fits a 32-bit float");
}

TEST(ScenarioSyntax, TopLevelValueMustBeAnObject) {
    expectError(errorForText("[1, 2, 3]"), "", "expected an object, got an array of 3 elements");
}

// --- Keys ----------------------------------------------------------------------------------

TEST(ScenarioKeys, UnknownKeySuggestsTheClosestKey) {
    json scenario = minimalScenario();
    scenario["frmaes"] = 10;
    expectError(scenario, "/frmaes", "unknown key 'frmaes'; did you mean 'frames'?");
}

TEST(ScenarioKeys, UnknownNestedKeyWithoutCloseMatchListsAllowedKeys) {
    json scenario = minimalScenario();
    scenario["viewport"] = {{"width", 800}, {"resolution", 2}};
    expectError(scenario, "/viewport/resolution", "allowed keys here: 'width', 'height'");
}

TEST(ScenarioKeys, MissingRequiredKeyIsReportedAtItsPointer) {
    json scenario = minimalScenario();
    scenario["scene"]["sources"][0].erase("type");
    expectError(scenario, "/scene/sources/0/type", "missing required key 'type'");
}

TEST(ScenarioCamera, NeedsExactlyOneOfKeyframesOrbitOrFly) {
    json scenario = minimalScenario();
    scenario["camera"].erase("keyframes");
    expectError(scenario, "/camera",
                "expected exactly one of 'keyframes', 'orbit' or 'fly', got 0");
    scenario = minimalScenario();
    scenario["camera"]["fly"] = {{"from", {0, 0, 0}}, {"to", {0, 0, -10}}, {"duration", 2}};
    expectError(scenario, "/camera", "got 2");
}

TEST(ScenarioCamera, OrbitHelperMakesALoopedCircleOfKeyframes) {
    json scenario = minimalScenario();
    scenario["camera"].erase("keyframes");
    scenario["camera"]["orbit"] = {
        {"center", {0, 0, 0}}, {"radius", 10}, {"height", 5}, {"period", 8}};
    const Scenario s = parseScenarioText(scenario.dump(), kFile);
    EXPECT_TRUE(s.camera.loop);
    ASSERT_GE(s.camera.keyframes.size(), 8u);
    EXPECT_DOUBLE_EQ(s.camera.keyframes.back().time_s, 8.0);
    for (const CameraKeyframe& k : s.camera.keyframes) {
        EXPECT_NEAR(glm::length(glm::dvec2(k.position.x, k.position.z)), 10.0, 1e-9);
        EXPECT_DOUBLE_EQ(k.position.y, 5.0);
        EXPECT_EQ(k.target, glm::dvec3(0.0));
    }
}

TEST(ScenarioCamera, FlyHelperGoesFromStartToEndLookingAhead) {
    json scenario = minimalScenario();
    scenario["camera"].erase("keyframes");
    scenario["camera"]["fly"] = {{"from", {0, 2, 0}}, {"to", {0, 2, -100}}, {"duration", 10}};
    const Scenario s = parseScenarioText(scenario.dump(), kFile);
    ASSERT_EQ(s.camera.keyframes.size(), 2u);
    EXPECT_EQ(s.camera.keyframes[1].position, glm::dvec3(0, 2, -100));
    EXPECT_DOUBLE_EQ(s.camera.keyframes[1].time_s, 10.0);
    EXPECT_LT(s.camera.keyframes[0].target.z, 0.0);
    scenario["camera"]["fly"]["to"] = {0, 2, 0};
    expectError(scenario, "/camera/fly/to", "must differ from 'from'");
}

TEST(ScenarioKeys, MissingRequiredKeyPointsAtALikelyMisspelling) {
    json scenario = minimalScenario();
    scenario["camrea"] = scenario["camera"];
    scenario.erase("camera");
    expectError(scenario, "/camera", "is 'camrea' a misspelling of it?");
}

TEST(ScenarioKeys, WrongFormatVersionIsRejected) {
    json scenario = minimalScenario();
    scenario["format_version"] = 2;
    expectError(scenario, "/format_version", "expected 1 (the only format_version");
}

TEST(ScenarioKeys, MissingFormatVersionIsRejected) {
    json scenario = minimalScenario();
    scenario.erase("format_version");
    expectError(scenario, "/format_version", "missing required key 'format_version'");
}

// --- Types ---------------------------------------------------------------------------------

TEST(ScenarioTypes, StringForANumberIsRejected) {
    json scenario = minimalScenario();
    scenario["frames"] = "ten";
    expectError(scenario, "/frames", "expected an integer in [1, 10000000], got \"ten\" (string)");
}

TEST(ScenarioTypes, FractionalValueForAnIntegerIsRejected) {
    json scenario = minimalScenario();
    scenario["frames"] = 2.5;
    expectError(scenario, "/frames", "got 2.5");
}

TEST(ScenarioTypes, IntegralFloatIsAcceptedAsAnInteger) {
    json scenario = minimalScenario();
    scenario["frames"] = 1e3;
    EXPECT_EQ(parseScenarioText(scenario.dump(), kFile).frames, 1000u);
}

TEST(ScenarioTypes, NegativeSeedIsRejected) {
    json scenario = minimalScenario();
    scenario["seed"] = -1;
    expectError(scenario, "/seed", "expected an integer >= 0, got -1");
}

TEST(ScenarioTypes, Vec3NeedsExactlyThreeNumbers) {
    json scenario = minimalScenario();
    scenario["camera"]["keyframes"][0]["position"] = {1, 2};
    expectError(scenario, "/camera/keyframes/0/position", "expected an array [x, y, z]");
}

TEST(ScenarioTypes, ExpectMustBeAnObject) {
    json scenario = minimalScenario();
    scenario["expect"] = json::array();
    expectError(scenario, "/expect", "expected an object");
}

// --- Ranges --------------------------------------------------------------------------------

TEST(ScenarioRanges, NonPositiveDtIsRejected) {
    json scenario = minimalScenario();
    scenario["dt"] = 0;
    expectError(scenario, "/dt", "expected a number in (0, 10], got 0");
}

TEST(ScenarioRanges, NearNotBelowFarIsRejected) {
    json scenario = minimalScenario();
    scenario["camera"]["near"] = 10;
    scenario["camera"]["far"] = 10;
    expectError(scenario, "/camera/far", "expected far > near");
}

TEST(ScenarioRanges, NegativeNearIsRejected) {
    json scenario = minimalScenario();
    scenario["camera"]["near"] = -1;
    expectError(scenario, "/camera/near", "expected a number > 0, got -1");
}

TEST(ScenarioRanges, FieldOfViewOutsideOpenIntervalIsRejected) {
    for (const double fov : {0.0, 180.0, -5.0, 200.0}) {
        json scenario = minimalScenario();
        scenario["camera"]["fov_y"] = fov;
        expectError(scenario, "/camera/fov_y", "expected a number in (0, 180)");
    }
}

TEST(ScenarioRanges, NegativeTeapotCountIsRejected) {
    json scenario = minimalScenario();
    scenario["scene"]["sources"][0]["count"] = -5;
    expectError(scenario, "/scene/sources/0/count", "expected an integer in [1, 1000000], got -5");
}

TEST(ScenarioRanges, NonIncreasingKeyframeTimesAreRejected) {
    json scenario = minimalScenario();
    auto& keys = scenario["camera"]["keyframes"];
    keys.push_back({{"time", 2}, {"position", {1, 2, 3}}, {"target", {0, 0, 0}}});
    keys.push_back({{"time", 2}, {"position", {2, 2, 3}}, {"target", {0, 0, 0}}});
    expectError(scenario, "/camera/keyframes/2/time", "keyframe times must strictly increase");
}

TEST(ScenarioRanges, KeyframeTargetEqualToPositionIsRejected) {
    json scenario = minimalScenario();
    scenario["camera"]["keyframes"][0]["target"] = {0, 2, 10};
    expectError(scenario, "/camera/keyframes/0/target", "target must differ from position");
}

TEST(ScenarioRanges, WarmupMustBeShorterThanTheRun) {
    json scenario = minimalScenario();
    scenario["frames"] = 5;
    scenario["warmup_frames"] = 5;
    expectError(scenario, "/warmup_frames", "expected an integer < frames (5), got 5");
}

TEST(ScenarioRanges, ReversedRegionIsRejected) {
    json scenario = minimalScenario();
    scenario["scene"]["sources"][0]["region"] = {{"min", {0, 0, 0}}, {"max", {1, -1, 1}}};
    expectError(scenario, "/scene/sources/0/region", "min.y = 0 > max.y = -1");
}

TEST(ScenarioRanges, ReversedSizeRangeIsRejected) {
    json scenario = minimalScenario();
    scenario["scene"]["sources"][0]["size"] = {3, 1};
    expectError(scenario, "/scene/sources/0/size", "min <= max");
}

TEST(ScenarioRanges, InvalidStatisticalOptionsReportTheDescriptorsRangeAtTheirKey) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"statistical", {{"decay_b", 1.5}}}};
    expectError(scenario, "/culling/statistical/decay_b", "expected a number in [0, 1], got 1.5");
}

TEST(ScenarioCulling, StatisticalPlusHasItsOwnOptionsWithEveryImprovementOn) {
    json scenario = minimalScenario();
    const Scenario plain = parseScenarioText(scenario.dump(), "x.json");
    EXPECT_FALSE(statisticalOf(plain).ready_answers) << "the paper by default";
    EXPECT_FALSE(statisticalOf(plain).cost_model);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").ready_answers);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").virtual_leaves);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").object_queries);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").cost_model);
    EXPECT_TRUE(statisticalOf(plain, "statistical+").fallback);
    EXPECT_GT(statisticalOf(plain, "statistical+").requery_parallax, 0.0);
    EXPECT_FALSE(plain.culler.cost_model.known()) << "measured at start-up unless given";

    scenario["culling"] = {
        {"algorithm", "statistical+"},
        {"statistical+",
         {{"fallback", false},
          {"requery_distance", 4.0},
          {"requery_parallax", 0},
          {"base_time", 0.5}}},
        {"statistical", {{"virtual_leaves", true}, {"object_queries", true}}},
        {"cost_model", {{"query_box_ms", 0.02}, {"triangle_ms", 6e-5}, {"draw_call_ms", 0.001}}}};
    const Scenario s = parseScenarioText(scenario.dump(), "x.json");
    EXPECT_EQ(s.algorithm, "statistical+");
    EXPECT_FALSE(statisticalOf(s, "statistical+").fallback);
    EXPECT_TRUE(statisticalOf(s, "statistical+").ready_answers)
        << "keys not given keep the plus defaults";
    EXPECT_DOUBLE_EQ(statisticalOf(s, "statistical+").requery_distance_m, 4.0);
    EXPECT_DOUBLE_EQ(statisticalOf(s, "statistical+").base_time_s, 0.5);
    EXPECT_TRUE(statisticalOf(s).virtual_leaves);
    EXPECT_TRUE(statisticalOf(s).object_queries);
    EXPECT_FALSE(statisticalOf(s).ready_answers);
    EXPECT_EQ(s.culler.cost_model, (CostModel{0.02, 6e-5, 0.001}));
}

TEST(ScenarioRanges, InvalidStatisticalPlusAndCostModelReportTheirObjects) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"statistical+", {{"requery_distance", 3.0}}}};
    expectError(scenario, "/culling/statistical+",
                "requery_distance and requery_parallax are alternatives");
    scenario["culling"] = {{"statistical+", {{"fallback_visible_share", 1.5}}}};
    expectError(scenario, "/culling/statistical+/fallback_visible_share",
                "expected a number in [0, 1], got 1.5");
    scenario["culling"] = {{"cost_model", {{"query_box_ms", -1.0}}}};
    expectError(scenario, "/culling/cost_model", "finite numbers >= 0");
    scenario["culling"] = {{"cost_model", {{"query_box_ms", 0.0}}}};
    expectError(scenario, "/culling/cost_model", "at least one figure > 0");
    scenario["culling"] = {{"cost_model", {{"query_ms", 0.1}}}};
    expectError(scenario, "/culling/cost_model/query_ms", "unknown key");
}

TEST(ScenarioRanges, InvalidPeerCullerOptionsReportTheDescriptorsRangeAtTheirKey) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"chc", {{"visible_frames_skip", 2000000}}}};
    expectError(scenario, "/culling/chc/visible_frames_skip",
                "expected an integer in [0, 1000000] (frames), got 2000000");
    scenario["culling"] = {{"chc++", {{"batch_size", 0}}}};
    expectError(scenario, "/culling/chc++/batch_size",
                "expected an integer in [1, 4294967295] (nodes), got 0");
    scenario["culling"] = {{"chc++", {{"tight_bounds_depth", 9}}}};
    expectError(scenario, "/culling/chc++/tight_bounds_depth",
                "expected an integer in [0, 6] (tree levels), got 9");
    scenario["culling"] = {{"chc++", {{"multiqueries", 1}}}};
    expectError(scenario, "/culling/chc++/multiqueries", "expected true or false");
    scenario["culling"] = {{"async", {{"retest_interval_frames", 0}}}};
    expectError(scenario, "/culling/async/retest_interval_frames",
                "expected an integer in [1, 1000000] (frames), got 0");
    scenario["culling"] = {{"async", {{"retest_interval", 3}}}};
    expectError(scenario, "/culling/async/retest_interval", "unknown key 'retest_interval'");
}

TEST(ScenarioCulling, PeerCullerOptionsAreRead) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"algorithm", "chc++"},
                           {"threshold_pixels", 25},
                           {"stale_results", true},
                           {"chc", {{"visible_frames_skip", 2}}},
                           {"chc++",
                            {{"visible_frames_skip", 7},
                             {"batch_size", 20},
                             {"multiqueries", false},
                             {"tight_bounds_depth", 2},
                             {"seed", 99}}},
                           {"async", {{"retest_interval_frames", 9}}}};
    const Scenario s = parseScenarioText(scenario.dump(), kFile);
    EXPECT_EQ(s.algorithm, "chc++");
    EXPECT_EQ(optionsOf(s, "chc").number("visible_frames_skip"), 2.0);
    EXPECT_EQ(s.culler.approximation.threshold_pixels, 25.0);
    EXPECT_TRUE(s.culler.approximation.stale_results);
    EXPECT_EQ(optionsOf(s, "chc++").number("visible_frames_skip"), 7.0);
    EXPECT_EQ(optionsOf(s, "chc++").number("batch_size"), 20.0);
    EXPECT_FALSE(optionsOf(s, "chc++").flag("multiqueries"));
    EXPECT_EQ(optionsOf(s, "chc++").number("tight_bounds_depth"), 2.0);
    EXPECT_EQ(optionsOf(s, "chc++").number("seed"), 99.0);
    EXPECT_EQ(optionsOf(s, "async").number("retest_interval_frames"), 9.0);
    const Scenario defaults = parseScenarioText(minimalScenario().dump(), kFile);
    EXPECT_EQ(optionsOf(defaults, "chc++").number("batch_size"), 50.0);
    EXPECT_EQ(optionsOf(defaults, "async").number("retest_interval_frames"), 5.0);
}

TEST(ScenarioRanges, InvalidBspOptionsReportIsValidMessage) {
    json scenario = minimalScenario();
    scenario["bsp"] = {{"max_depth", 65}};
    expectError(scenario, "/bsp", "max_depth must be in [0, 64]");
}

// --- Enumerations and movers ---------------------------------------------------------------

TEST(ScenarioSources, OccludersSaysWhetherASourcesObjectsOccludeInMasked) {
    json scenario = minimalScenario();
    EXPECT_EQ(parseScenarioText(scenario.dump(), kFile).sources.at(0).occluders,
              OccluderRole::BySize);
    scenario["scene"]["sources"][0]["occluders"] = "never";
    EXPECT_EQ(parseScenarioText(scenario.dump(), kFile).sources.at(0).occluders,
              OccluderRole::Never);
    scenario["scene"]["sources"][0]["occluders"] = "always";
    EXPECT_EQ(parseScenarioText(scenario.dump(), kFile).sources.at(0).occluders,
              OccluderRole::Always);
    scenario["scene"]["sources"][0]["occluders"] = "sometimes";
    expectError(scenario, "/scene/sources/0/occluders",
                "expected one of \"by_size\", \"always\", \"never\"");
    scenario["scene"]["sources"][0]["occluders"] = true;
    expectError(scenario, "/scene/sources/0/occluders", "expected one of");
}

TEST(ScenarioEnums, UnknownAlgorithmListsValidNames) {
    json scenario = minimalScenario();
    scenario["culling"] = {{"algorithm", "statstical"}};
    // Every registered culler, in the registry's order (the list is the registry's, not typed).
    std::string names;
    for (const std::string& n : cullerNames()) names += (names.empty() ? "\"" : ", \"") + n + "\"";
    EXPECT_NE(names.find("\"vfc\", \"stop-and-wait\", \"statistical\""), std::string::npos);
    expectError(scenario, "/culling/algorithm",
                "expected one of " + names + " (did you mean \"statistical\"?), got " +
                    "\"statstical\" (string)");
}

TEST(ScenarioEnums, UnknownSourceTypeListsValidTypes) {
    json scenario = minimalScenario();
    scenario["scene"]["sources"][0]["type"] = "terrain";
    expectError(scenario, "/scene/sources/0/type",
                "expected one of \"teapots\", \"gltf\", \"city\", \"library\", \"plant\"");
}

TEST(ScenarioMovers, OrbitWithRegionIsRejected) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.1},
                           {"motion", "orbit"},
                           {"region", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}}};
    expectError(scenario, "/movers/0/region", "'region' is not allowed with motion \"orbit\"");
}

TEST(ScenarioMovers, BounceWithRadiusIsRejected) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.1}, {"motion", "bounce"}, {"radius", {1, 2}}}};
    expectError(scenario, "/movers/0/radius", "'radius' is not allowed with motion \"bounce\"");
}

TEST(ScenarioMovers, NeedExactlyOneSelection) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"motion", "bounce"}}};
    expectError(scenario, "/movers/0", "expected exactly one of 'fraction', 'objects' or 'spawn'");
    scenario["movers"] = {{{"motion", "bounce"}, {"fraction", 0.1}, {"objects", {1}}}};
    expectError(scenario, "/movers/0", "got 2");
}

TEST(ScenarioMovers, EveryMotionTypeParsesWithItsOwnKeys) {
    json scenario = minimalScenario();
    scenario["movers"] = {
        {{"spawn", {{"count", 5}, {"shape", "box"}, {"size", {1, 2}}}},
         {"motion", "path"},
         {"waypoints", {{0, 0, 0}, {10, 0, 0}, {10, 0, 10}}},
         {"speed", {3, 5}}},
        {{"objects", {0}}, {"motion", "spin"}, {"spin", {10, 20}}},
        {{"fraction", 0.2}, {"motion", "random_walk"}, {"turn_rate", 45}, {"speed", {1, 1}}},
    };
    const Scenario s = parseScenarioText(scenario.dump(), kFile);
    ASSERT_EQ(s.movers.size(), 3u);
    EXPECT_EQ(s.movers[0].selection, MoverSelection::Spawn);
    EXPECT_EQ(s.movers[0].spawn.shape, SpawnShape::Box);
    EXPECT_EQ(s.movers[0].waypoints.size(), 3u);
    EXPECT_EQ(s.movers[1].motion, MotionType::Spin);
    EXPECT_DOUBLE_EQ(s.movers[1].spin_max_deg_s, 20.0);
    EXPECT_EQ(s.movers[2].motion, MotionType::RandomWalk);
    EXPECT_DOUBLE_EQ(s.movers[2].turn_rate_deg_s, 45.0);
}

TEST(ScenarioMovers, KeysOfAnotherMotionAreRejected) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.1}, {"motion", "spin"}, {"speed", {1, 2}}}};
    expectError(scenario, "/movers/0/speed", "'speed' is not allowed with motion \"spin\"");
    scenario["movers"] = {
        {{"fraction", 0.1}, {"motion", "bounce"}, {"waypoints", {{0, 0, 0}, {1, 0, 0}}}}};
    expectError(scenario, "/movers/0/waypoints", "applies to path only");
}

TEST(ScenarioMovers, SourceIndexMustExist) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.1}, {"motion", "bounce"}, {"source", 1}}};
    expectError(scenario, "/movers/0/source", "which has 1 entry, got 1");
}

TEST(ScenarioMovers, MotionIsRequired) {
    json scenario = minimalScenario();
    scenario["movers"] = {{{"fraction", 0.5}}};
    expectError(scenario, "/movers/0/motion", "missing required key 'motion'");
}

// --- Valid input ---------------------------------------------------------------------------

TEST(ScenarioDefaults, MinimalScenarioGetsAllDocumentedDefaults) {
    const Scenario s = parseScenarioText(minimalScenario().dump(), "dir/teapot-field.json");
    const Scenario defaults;
    const TeapotFieldSpec teapot_defaults;
    const StatisticalOptions statistical_defaults;
    const BspBuildOptions bsp_defaults;

    EXPECT_EQ(s.file, std::filesystem::path("dir/teapot-field.json"));
    EXPECT_EQ(s.name, "teapot-field");
    EXPECT_EQ(s.seed, 1u);
    EXPECT_EQ(s.frames, 300u);
    EXPECT_DOUBLE_EQ(s.dt_s, 1.0 / 30.0);
    EXPECT_EQ(s.warmup_frames, 10u);
    EXPECT_EQ(s.width, 640u);
    EXPECT_EQ(s.height, 480u);
    EXPECT_DOUBLE_EQ(s.camera.fov_y_deg, 60.0);
    EXPECT_DOUBLE_EQ(s.camera.near_m, 0.1);
    EXPECT_DOUBLE_EQ(s.camera.far_m, 1000.0);
    EXPECT_FALSE(s.camera.loop);
    ASSERT_EQ(s.camera.keyframes.size(), 1u);
    EXPECT_EQ(s.camera.keyframes[0].position, glm::dvec3(0, 2, 10));
    EXPECT_EQ(s.camera.keyframes[0].target, glm::dvec3(0, 2, 0));

    ASSERT_EQ(s.sources.size(), 1u);
    const auto& t = std::get<TeapotFieldSpec>(s.sources[0].spec);
    EXPECT_EQ(s.sources[0].type, SourceType::Teapots);
    EXPECT_EQ(t.count, 1000u);
    EXPECT_EQ(t.region.min, glm::dvec3(-50, 0, -200));
    EXPECT_EQ(t.region.max, glm::dvec3(50, 10, 0));
    EXPECT_EQ(t.region.min, teapot_defaults.region.min);
    EXPECT_DOUBLE_EQ(t.size_min_m, 1.0);
    EXPECT_DOUBLE_EQ(t.size_max_m, 3.0);
    EXPECT_EQ(t.tessellation, 6u);

    EXPECT_TRUE(s.movers.empty());
    EXPECT_EQ(s.algorithm, "statistical");
    EXPECT_DOUBLE_EQ(statisticalOf(s).base_time_s, statistical_defaults.base_time_s);
    EXPECT_DOUBLE_EQ(statisticalOf(s).decay_a, 2.0);
    EXPECT_DOUBLE_EQ(statisticalOf(s).decay_b, 0.5);
    EXPECT_EQ(statisticalOf(s).history_length, 8u);
    EXPECT_DOUBLE_EQ(statisticalOf(s).max_statistics_age_s, 2.0);
    EXPECT_EQ(statisticalOf(s).queries_before_restart, 20u);
    EXPECT_EQ(s.bsp.max_depth, bsp_defaults.max_depth);
    EXPECT_EQ(s.bsp.max_objects_per_leaf, 4u);
    EXPECT_EQ(s.bsp.split_rule, BspSplitRule::Median);
    EXPECT_FLOAT_EQ(s.bsp.root_margin, 0.05f);
    EXPECT_FALSE(s.expect.has_value());
    EXPECT_EQ(s.seed, defaults.seed);
}

TEST(ScenarioDefaults, WarmupDefaultShrinksForShortRuns) {
    json scenario = minimalScenario();
    scenario["frames"] = 4;
    EXPECT_EQ(parseScenarioText(scenario.dump(), kFile).warmup_frames, 3u);
}

TEST(ScenarioValid, EveryKeyIsReadIntoTheScenario) {
    json scenario = minimalScenario();
    scenario["name"] = "everything";
    scenario["seed"] = 18446744073709551615ull;
    scenario["frames"] = 50;
    scenario["dt"] = 0.02;
    scenario["warmup_frames"] = 0;
    scenario["viewport"] = {{"width", 320}, {"height", 200}};
    scenario["camera"]["fov_y"] = 45;
    scenario["camera"]["loop"] = true;
    scenario["scene"]["sources"][0] = {{"type", "teapots"},
                                       {"count", 20},
                                       {"region", {{"min", {-1, -2, -3}}, {"max", {1, 2, 3}}}},
                                       {"size", {0.5, 0.5}},
                                       {"tessellation", 2}};
    scenario["movers"] = {
        {{"motion", "bounce"},
         {"fraction", 0.5},
         {"speed", {0, 2}},
         {"region", {{"min", {0, 0, 0}}, {"max", {4, 4, 4}}}}},
        {{"source", 0}, {"motion", "orbit"}, {"fraction", 1}, {"radius", {1, 1}}}};
    scenario["culling"] = {{"algorithm", "vfc"},
                           {"statistical", {{"base_time", 1}, {"history_length", 4}}}};
    scenario["bsp"] = {{"split", "sah"},    {"max_depth", 12}, {"root_margin", 0},
                       {"looseness", 0.25}, {"adapt", false},  {"max_root_growth", 4}};
    scenario["expect"] = {
        {"algorithms", {"vfc", "async"}}, {"frames", 20}, {"max_error_pixels", {{"async", 50}}}};

    const Scenario s = parseScenarioText(scenario.dump(), kFile);
    EXPECT_EQ(s.name, "everything");
    EXPECT_EQ(s.seed, 18446744073709551615ull);
    EXPECT_EQ(s.frames, 50u);
    EXPECT_DOUBLE_EQ(s.dt_s, 0.02);
    EXPECT_EQ(s.warmup_frames, 0u);
    EXPECT_EQ(s.width, 320u);
    EXPECT_EQ(s.height, 200u);
    EXPECT_DOUBLE_EQ(s.camera.fov_y_deg, 45.0);
    EXPECT_TRUE(s.camera.loop);
    const auto& t = std::get<TeapotFieldSpec>(s.sources[0].spec);
    EXPECT_EQ(t.count, 20u);
    EXPECT_EQ(t.region.min, glm::dvec3(-1, -2, -3));
    EXPECT_EQ(t.region.max, glm::dvec3(1, 2, 3));
    EXPECT_DOUBLE_EQ(t.size_min_m, 0.5);
    EXPECT_EQ(t.tessellation, 2u);
    ASSERT_EQ(s.movers.size(), 2u);
    EXPECT_EQ(s.movers[0].motion, MotionType::Bounce);
    EXPECT_TRUE(s.movers[0].has_region);
    EXPECT_EQ(s.movers[0].region.max, glm::dvec3(4, 4, 4));
    EXPECT_DOUBLE_EQ(s.movers[0].speed_min_mps, 0.0);
    EXPECT_DOUBLE_EQ(s.movers[0].fraction, 0.5);
    EXPECT_EQ(s.movers[1].motion, MotionType::Orbit);
    EXPECT_FALSE(s.movers[1].has_region);
    EXPECT_DOUBLE_EQ(s.movers[1].radius_max_m, 1.0);
    EXPECT_EQ(s.algorithm, "vfc");
    EXPECT_DOUBLE_EQ(statisticalOf(s).base_time_s, 1.0);
    EXPECT_EQ(statisticalOf(s).history_length, 4u);
    EXPECT_EQ(s.bsp.split_rule, BspSplitRule::Sah);
    EXPECT_EQ(s.bsp.max_depth, 12u);
    EXPECT_FLOAT_EQ(s.bsp.root_margin, 0.0f);
    EXPECT_FLOAT_EQ(s.bsp.looseness, 0.25f);
    EXPECT_FALSE(s.bsp.adapt);
    EXPECT_FLOAT_EQ(s.bsp.max_root_growth, 4.0f);
    ASSERT_TRUE(s.expect.has_value());
    EXPECT_EQ(s.expect->algorithms, (std::vector<std::string>{"vfc", "async"}));
    EXPECT_EQ(s.expect->frames, 20u);
    EXPECT_EQ(s.expect->zero_error, std::vector<std::string>{"vfc"}) << "the conservative ones";
    EXPECT_EQ(s.expect->max_error_pixels.at("async"), 50);
}

// The expect block is read with the rest of the scenario: a mistake in it is a parse error.
TEST(ScenarioExpect, IsParsedWithTheScenario) {
    json scenario = minimalScenario();
    scenario["expect"] = {{"anything", {1, 2, 3}}};
    expectError(scenario, "/expect/anything", "unknown key 'anything'");
    scenario["expect"] = {{"algorithms", {"vfc", "nope"}}};
    expectError(scenario, "/expect/algorithms/1", "expected one of");
}

// Mover object indices are checked by the parser where the source's spec tells its object count.
TEST(ScenarioMovers, ObjectIndicesPastATeapotFieldAreRejectedByTheParser) {
    json scenario = minimalScenario();
    scenario["scene"]["sources"][0] = {{"type", "teapots"}, {"count", 5}};
    scenario["movers"] = {{{"motion", "spin"}, {"objects", {0, 4, 5}}}};
    expectError(scenario, "/movers/0/objects/2", "expected an object index < 5");
}

// Every ```json block of docs/scenario*.md is a complete scenario that parses. Paths inside the
// examples are written as in a file in scenarios/ (e.g. "assets/FZK-Haus/AC14-FZK-Haus.glb").
TEST(ScenarioDocs, EveryJsonExampleInTheScenarioDocumentsParses) {
    const std::filesystem::path docs = std::filesystem::path(OCCSIM_SOURCE_DIR) / "docs";
    const std::filesystem::path as_if =
        std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios" / "doc-example.json";
    std::size_t total = 0;
    for (const auto& entry : std::filesystem::directory_iterator(docs)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("scenario", 0) != 0 || entry.path().extension() != ".md") continue;
        const std::vector<std::string> blocks = jsonBlocks(readText(entry.path()));
        for (std::size_t i = 0; i < blocks.size(); ++i) {
            SCOPED_TRACE("```json block " + std::to_string(i + 1) + " of " + name);
            EXPECT_NO_THROW(parseScenarioText(blocks[i], as_if));
        }
        total += blocks.size();
    }
    EXPECT_GE(total, 2u) << "expected complete ```json examples in " << docs;
}

// --- The reader's helpers ------------------------------------------------------------------

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

// The one parser of numbers typed as text (--sweep, --params, view scripts) keeps what each of
// the three copies it replaced took: stod's syntax for doubles, from_chars' for integers.
TEST(NumberText, FiniteNumbersUseTheWholeTextAndRefuseInfinities) {
    double v = 0;
    EXPECT_TRUE(parseFiniteNumber("1.5", v));
    EXPECT_EQ(v, 1.5);
    EXPECT_TRUE(parseFiniteNumber("-2e3", v));
    EXPECT_EQ(v, -2000.0);
    EXPECT_TRUE(parseFiniteNumber(" 4", v)) << "stod skips leading spaces, as the flags did";
    EXPECT_EQ(v, 4.0);
    for (const char* bad : {"", "x", "1.5x", "4 ", "inf", "nan", "1e999", "true"}) {
        EXPECT_FALSE(parseFiniteNumber(bad, v)) << "'" << bad << "'";
    }
}

TEST(NumberText, IntegersUseTheWholeTextWithoutSpacesOrPlus) {
    int64_t v = 0;
    EXPECT_TRUE(parseInteger("42", v));
    EXPECT_EQ(v, 42);
    EXPECT_TRUE(parseInteger("-7", v));
    EXPECT_EQ(v, -7);
    for (const char* bad : {"", "+1", " 1", "1 ", "1.0", "0x10", "99999999999999999999"}) {
        EXPECT_FALSE(parseInteger(bad, v)) << "'" << bad << "'";
    }
}

// --- Option values in JSON (option_json.h) --------------------------------------------------

TEST(OptionJson, WritesEachOptionInItsJsonTypeInDescriptorOrder) {
    const nlohmann::ordered_json j = optionValuesJson(OptionValues(findCuller("chc++")->options));
    EXPECT_EQ(j.dump(), R"({"visible_frames_skip":2,"batch_size":50,"multiqueries":true,)"
                        R"("tight_bounds_depth":2,"seed":1})");
    EXPECT_TRUE(j["seed"].is_number_integer());
    EXPECT_EQ(optionValuesJson(OptionValues()).dump(), "{}");
}

TEST(OptionJson, ANegativeIntegerIsWrittenAsItself) {
    const OptionsDescriptor d = {integerOption("offset", "", -10, 10, -3, "may be negative")};
    EXPECT_EQ(optionValuesJson(OptionValues(d)).dump(), R"({"offset":-3})");
}

TEST(OptionJson, EveryCullersValuesReadBackAsWritten) {
    for (const CullerRow* culler : cullerRows()) {
        const OptionValues written(culler->options);
        const Json j(optionValuesJson(written));
        OptionValues read(culler->options);
        for (const OptionSpec& spec : culler->options) {
            read.set(
                spec.key,
                readOptionValue(JsonValueReader(j.at(spec.key), "/" + spec.key, "t.json"), spec));
        }
        EXPECT_TRUE(read == written) << culler->name;
    }
}

TEST(OptionJson, AValueOfTheWrongTypeOrRangeFailsAtItsPointer) {
    const OptionSpec spec = integerOption("n", "frames", 1, 8, 1, "a count");
    const Json text = "4";
    const Json big = 9;
    try {
        readOptionValue(JsonValueReader(text, "/culling/x/n", "t.json"), spec);
        FAIL() << "a string was read as an integer";
    } catch (const ScenarioError& e) {
        EXPECT_STREQ(e.what(),
                     "t.json: /culling/x/n: expected an integer in [1, 8] (frames), "
                     "got \"4\" (string)");
    }
    try {
        readOptionValue(JsonValueReader(big, "/culling/x/n", "t.json"), spec);
        FAIL() << "9 was read in [1, 8]";
    } catch (const ScenarioError& e) {
        EXPECT_STREQ(e.what(),
                     "t.json: /culling/x/n: expected an integer in [1, 8] (frames), got 9");
    }
}

}  // namespace
}  // namespace occsim
