// One identity per scenario of a regression run (sim/regress/scenario_identity.h): distinct
// paths give distinct ids, and a set where two scenarios would share a folder, or one file comes
// twice, is refused before anything runs, one line per problem.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "occsim/culling/contract/input_error.h"
#include "sim/output/run_folder.h"
#include "sim/regress/regress.h"
#include "sim/regress/scenario_identity.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("occsim-identity-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void touch(const fs::path& file) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << "{}";
}

std::string refusal(const std::vector<fs::path>& inputs) {
    try {
        collectScenarioFiles(inputs);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ScenarioIdentity, AnIdIsThePathBelowTheFolderGivenAsOneSafeComponent) {
    EXPECT_EQ(scenarioId("teapots.json"), "teapots");
    EXPECT_EQ(scenarioId("paper/city.json"), "paper+city");
    EXPECT_EQ(scenarioId("x/scene.json"), "x+scene");
    EXPECT_EQ(scenarioId("a b.json"), "a%20b");
    EXPECT_EQ(scenarioId("\xC3\x9F.json"), "%C3%9F");  // ß
    EXPECT_EQ(scenarioId(".hidden.json"), "%2Ehidden");
    EXPECT_EQ(scenarioId("v1.2.json"), "v1.2");
}

TEST(ScenarioIdentity, DistinctPathsNeverShareAnId) {
    // What safeFileName() made one: '+' and '/', letters outside ASCII, '%' itself.
    const std::vector<std::string> paths = {
        "a+b.json",      "a/b.json",      "a_b.json",          "a%2Bb.json",
        "\xC3\xA4.json", "\xC3\xB6.json", "\xE6\x97\xA5.json", "\xE4\xB8\xAD.json"};
    std::set<std::string> ids;
    for (const std::string& p : paths) ids.insert(scenarioId(p));
    EXPECT_EQ(ids.size(), paths.size());
    for (const std::string& id : ids) {
        EXPECT_EQ(id.find('/'), std::string::npos) << id;
        EXPECT_NE(id.front(), '.') << id;
    }
}

TEST(ScenarioIdentity, SameNamedFilesInTwoSubfoldersOfOneInputGetTwoIds) {
    const fs::path dir = freshDir("subfolders");
    touch(dir / "x" / "scene.json");
    touch(dir / "y" / "scene.json");
    const std::vector<ScenarioFile> found = collectScenarioFiles({dir});
    ASSERT_EQ(found.size(), 2u);
    EXPECT_EQ(found[0].id, "x+scene");
    EXPECT_EQ(found[1].id, "y+scene");
    fs::remove_all(dir);
}

TEST(ScenarioIdentity, SameNamedFilesFromTwoInputsAreRefusedBeforeAnyRun) {
    const fs::path dir = freshDir("two-inputs");
    touch(dir / "x" / "scene.json");
    touch(dir / "y" / "scene.json");
    const std::string e = refusal({dir / "x", dir / "y"});
    EXPECT_NE(e.find("both would write the results folder 'scene'"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "one problem, one line: " << e;
    const std::string files = refusal({dir / "x" / "scene.json", dir / "y" / "scene.json"});
    EXPECT_NE(files.find("'scene'"), std::string::npos) << files;
    fs::remove_all(dir);
}

TEST(ScenarioIdentity, OneFileReachedTwiceIsRefused) {
    const fs::path dir = freshDir("twice");
    touch(dir / "m" / "a.json");
    touch(dir / "m" / "b.json");
    const std::string e = refusal({dir / "m", dir / "." / "m"});
    EXPECT_NE(e.find("the same file as"), std::string::npos) << e;
    EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << "two files, two lines: " << e;
    EXPECT_NE(refusal({dir / "m" / "a.json", dir / "m"}).find("given twice"), std::string::npos);
    EXPECT_NE(refusal({dir / "m" / "a.json", dir / "m" / "a.json"}).find("given twice"),
              std::string::npos);
    fs::remove_all(dir);
}

TEST(ScenarioIdentity, FoldersAnOccsimRunWroteAreNeverSearchedForScenarios) {
    const fs::path dir = freshDir("outputs");
    touch(dir / "s.json");
    touch(dir / "out" / "s" / "summary.json");
    touch(dir / "out" / "shard.json");
    std::ofstream(dir / "out" / kRegressMarker) << "";
    touch(dir / "run" / "summary.json");
    std::ofstream(dir / "run" / kRunMarker) << "";
    const std::vector<ScenarioFile> found = collectScenarioFiles({dir});
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].file, dir / "s.json");
    fs::remove_all(dir);
}

}  // namespace
}  // namespace occsim
