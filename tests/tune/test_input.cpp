// What the tuner checks before any run (tune/input.h): an option the scene gives nothing to act
// on is left out of the fit with why, and a session left with nothing to tune is refused with one
// line. Issue 56: occtune tuned masked's occluder_size on a scene whose every object had an
// explicit occluder role, and its verdict said nothing of it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tune/errors.h"
#include "tune/input.h"

namespace occsim::tune {
namespace {

namespace fs = std::filesystem;

// A culler with two tunable options: one acting on every object, one only on the occluders whose
// role is chosen by size.
CullerRow twoKnobs() {
    CullerRow row;
    row.name = "two-knobs";
    row.options = {
        tunable(numberOption("reach", "m", 0.0, 10.0, 1.0, "acts everywhere"), 0.0, 5.0),
        actingOn(tunable(numberOption("size", "", 0.0, 1.0, 0.2, "acts on by-size"), 0.0, 0.5),
                 OptionScope::OccludersBySize)};
    return row;
}

OccluderRoleCounts explicitRoles() {
    OccluderRoleCounts roles;
    roles.always = 11;
    roles.never = 41;
    return roles;
}

TEST(LeaveOutInertParameters, AnOptionOnOccludersBySizeGoesWhenEveryRoleIsExplicit) {
    const CullerRow row = twoKnobs();
    ParameterSpace space = parseParameterSpace(row, "", {});
    const std::vector<std::string> left = leaveOutInertParameters(space, explicitRoles());
    ASSERT_EQ(space.size(), 1u);
    EXPECT_EQ(space.parameters[0].name, "reach");
    ASSERT_EQ(space.bounds.size(), 1u);
    EXPECT_DOUBLE_EQ(space.bounds[0].hi, 5.0);
    ASSERT_EQ(left.size(), 1u);
    EXPECT_EQ(left[0],
              "size: no object's occluder role is chosen by size (0 by size, 11 always, 41 never; "
              "0 with an authored occluder mesh), so it cannot act");
}

TEST(LeaveOutInertParameters, OneObjectChosenBySizeKeepsIt) {
    const CullerRow row = twoKnobs();
    ParameterSpace space = parseParameterSpace(row, "", {});
    OccluderRoleCounts roles = explicitRoles();
    roles.by_size = 1;
    EXPECT_TRUE(leaveOutInertParameters(space, roles).empty());
    EXPECT_EQ(space.size(), 2u);
}

TEST(LeaveOutInertParameters, NothingLeftToTuneIsOneLine) {
    const CullerRow row = twoKnobs();
    ParameterSpace space = parseParameterSpace(row, "size", {});
    try {
        leaveOutInertParameters(space, explicitRoles());
        FAIL() << "expected a TuneInputError";
    } catch (const TuneInputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("--params: nothing left to tune on this scene: size: no object's", 0),
                  0u)
            << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

// A scenario of a few teapots whose occluder role is `occluders` ("" for the default, by size).
fs::path teapotScenario(const std::string& name, const std::string& occluders) {
    nlohmann::json source = {{"type", "teapots"}, {"count", 12}};
    if (!occluders.empty()) source["occluders"] = occluders;
    const nlohmann::json scenario = {
        {"format_version", 1},
        {"name", name},
        {"frames", 20},
        {"camera",
         {{"keyframes", {{{"time", 0}, {"position", {0, 2, 10}}, {"target", {0, 2, 0}}}}}}},
        {"scene", {{"sources", {source}}}}};
    const fs::path dir =
        fs::temp_directory_path() / ("occtune-input-" + std::to_string(::getpid()) + "-" + name);
    fs::create_directories(dir);
    std::ofstream(dir / "scenario.json") << scenario.dump();
    return dir / "scenario.json";
}

TEST(CheckInput, MaskedOnASceneOfExplicitRolesHasNothingToTuneAndSaysWhy) {
    TuneOptions o;
    o.scenario = teapotScenario("never", "never");
    o.algorithm = "masked";
    try {
        checkInput(o);
        FAIL() << "expected a TuneInputError";
    } catch (const TuneInputError& e) {
        EXPECT_NE(std::string(e.what()).find("occluder_size: no object's occluder role is chosen "
                                             "by size (0 by size, 0 always, 12 never;"),
                  std::string::npos)
            << e.what();
    }
    // The statistical culler's options act on every object: nothing left out.
    o.algorithm = "statistical";
    const CheckedInput statistical = checkInput(o);
    EXPECT_TRUE(statistical.left_out.empty());
    EXPECT_EQ(statistical.space.size(), tunableParameters(*findCuller("statistical")).size());
    fs::remove_all(o.scenario.parent_path());
}

TEST(CheckInput, MaskedOnASceneOfRolesBySizeTunesOccluderSize) {
    TuneOptions o;
    o.scenario = teapotScenario("by-size", "");
    o.algorithm = "masked";
    const CheckedInput c = checkInput(o);
    EXPECT_TRUE(c.left_out.empty());
    ASSERT_EQ(c.space.size(), 1u);
    EXPECT_EQ(c.space.parameters[0].name, "occluder_size");
    fs::remove_all(o.scenario.parent_path());
}

}  // namespace
}  // namespace occsim::tune
