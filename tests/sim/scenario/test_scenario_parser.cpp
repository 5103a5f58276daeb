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

#include "scenario_fixtures.h"

namespace occsim {
namespace {

using namespace fixtures;

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

}  // namespace
}  // namespace occsim
