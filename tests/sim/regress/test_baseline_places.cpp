// Where a regression run may read and write baselines (sim/regress/baseline_places.h): in the
// scenario's own folder, never a scenario file, never shared, and --update never overwrites a
// file that is not an occsim baseline.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "sim/regress/baseline_places.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

struct Tree {
    fs::path root;
    explicit Tree(const std::string& name)
        : root(fs::temp_directory_path() /
               ("occsim-baselines-" + std::to_string(::getpid()) + "-" + name)) {
        fs::remove_all(root);
        fs::create_directories(root / "scenarios" / "sub");
    }
    ~Tree() { fs::remove_all(root); }
    fs::path write(const std::string& rel, const std::string& text = "{}") const {
        fs::create_directories((root / rel).parent_path());
        std::ofstream(root / rel) << text;
        return root / rel;
    }
};

std::vector<std::string> problems(const std::vector<BaselinePlace>& places,
                                  const std::vector<fs::path>& scenarios, bool update = false) {
    return baselinePlaceProblems(places, scenarios, update);
}

TEST(BaselinePlaces, TheDefaultPlaceAndAFolderBelowTheScenarioAreGood) {
    Tree t("good");
    const fs::path s = t.write("scenarios/a.json");
    EXPECT_TRUE(problems({{s, s.parent_path() / "a.baseline.json", ""}}, {s}).empty());
    EXPECT_TRUE(problems({{s, s.parent_path() / "sub" / "a.baseline.json", ""}}, {s}).empty());
}

TEST(BaselinePlaces, TheScenarioFileItselfIsRefused) {
    Tree t("self");
    const fs::path s = t.write("scenarios/self.json");
    const auto p = problems({{s, s.parent_path() / "self.json", ""}}, {s}, true);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_NE(p[0].find("/expect/baseline"), std::string::npos) << p[0];
    EXPECT_NE(p[0].find("is the scenario file itself"), std::string::npos) << p[0];
    EXPECT_FALSE(problems({{s, s.parent_path() / "self.json", ""}}, {s}, false).empty())
        << "refused without --update too: the check would read the scenario as a baseline";
}

TEST(BaselinePlaces, AnotherScenarioOfTheRunIsRefused) {
    Tree t("other");
    const fs::path a = t.write("scenarios/a.json"), b = t.write("scenarios/b.json");
    const auto p = problems({{a, a.parent_path() / "b.json", ""}}, {a, b});
    ASSERT_EQ(p.size(), 1u);
    EXPECT_NE(p[0].find("is a scenario file of this run"), std::string::npos) << p[0];
}

TEST(BaselinePlaces, APlaceOutsideTheScenariosFolderIsRefused) {
    Tree t("outside");
    const fs::path s = t.write("scenarios/sub/up.json");
    for (const char* rel : {"../../x.json", "../x.baseline.json", "/tmp/x.baseline.json"}) {
        const auto p = problems({{s, s.parent_path() / rel, ""}}, {s});
        ASSERT_EQ(p.size(), 1u) << rel;
        EXPECT_NE(p[0].find("lies outside the scenario's folder"), std::string::npos) << p[0];
    }
}

TEST(BaselinePlaces, ASymlinkLeadingOutOfTheFolderIsRefused) {
    Tree t("symlink");
    const fs::path s = t.write("scenarios/a.json");
    const fs::path far = t.write("elsewhere/x.baseline.json");
    fs::create_symlink(far, s.parent_path() / "a.baseline.json");
    const auto p = problems({{s, s.parent_path() / "a.baseline.json", ""}}, {s});
    ASSERT_EQ(p.size(), 1u);
    EXPECT_NE(p[0].find("lies outside"), std::string::npos) << p[0];
}

TEST(BaselinePlaces, OneBaselineForTwoScenariosIsRefused) {
    Tree t("shared");
    const fs::path a = t.write("scenarios/a.json"), b = t.write("scenarios/b.json");
    const fs::path shared = a.parent_path() / "shared.baseline.json";
    const auto p = problems({{a, shared, ""}, {b, shared, ""}}, {a, b});
    ASSERT_EQ(p.size(), 1u);
    EXPECT_NE(p[0].find("is also the baseline of"), std::string::npos) << p[0];
}

TEST(BaselinePlaces, UpdateNeverOverwritesAFileThatIsNotABaseline) {
    Tree t("not-ours");
    const fs::path s = t.write("scenarios/a.json");
    const fs::path notes = t.write("scenarios/notes.txt", "my notes");
    EXPECT_TRUE(problems({{s, notes, ""}}, {s}, false).empty())
        << "reading it only fails its check";
    const auto p = problems({{s, notes, ""}}, {s}, true);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_NE(p[0].find("is not an occsim baseline file"), std::string::npos) << p[0];
    // An older baseline (another version) is ours: --update rewrites it.
    const fs::path old =
        t.write("scenarios/old.baseline.json", R"({"format": "occsim-baseline", "version": 1})");
    EXPECT_TRUE(problems({{s, old, ""}}, {s}, true).empty());
    EXPECT_TRUE(isOccsimBaselineFile(old));
    EXPECT_FALSE(isOccsimBaselineFile(notes));
}

// Scenario one's expect.baseline naming scenario two's baseline: --update refuses to write over
// it (it records another scenario), whatever the run holds; its own baseline it rewrites.
TEST(BaselinePlaces, UpdateNeverWritesOverAnotherScenariosBaseline) {
    Tree t("other-scenario");
    const fs::path one = t.write("scenarios/one.json");
    const fs::path two_baseline =
        t.write("scenarios/two.baseline.json",
                R"({"format": "occsim-baseline", "version": 2, "scenario": "two"})");
    EXPECT_EQ(baselineScenarioName(two_baseline), "two");
    const auto p = problems({{one, two_baseline, "one"}}, {one}, true);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_NE(p[0].find("is the baseline of the scenario 'two', not 'one'"), std::string::npos)
        << p[0];
    EXPECT_TRUE(problems({{one, two_baseline, "one"}}, {one}, false).empty());
    EXPECT_TRUE(problems({{one, two_baseline, "two"}}, {one}, true).empty());
}

// A folder where a baseline is named: one line before anything runs, checking or updating.
TEST(BaselinePlaces, AFolderNamedAsTheBaselineIsRefused) {
    Tree t("folder");
    const fs::path s = t.write("scenarios/a.json");
    fs::create_directories(t.root / "scenarios" / "a.baseline.json");
    for (const bool update : {false, true}) {
        const auto p = problems({{s, t.root / "scenarios" / "a.baseline.json", "a"}}, {s}, update);
        ASSERT_EQ(p.size(), 1u);
        EXPECT_NE(p[0].find("is a folder; expected a file"), std::string::npos) << p[0];
    }
}

TEST(BaselinePlaces, EveryProblemIsOneLine) {
    Tree t("lines");
    const fs::path a = t.write("scenarios/a.json"), b = t.write("scenarios/b.json");
    const auto p = problems({{a, a, ""}, {b, b.parent_path() / "../../x.json", ""}}, {a, b});
    ASSERT_EQ(p.size(), 2u);
    for (const std::string& line : p) EXPECT_EQ(line.find('\n'), std::string::npos) << line;
}

}  // namespace
}  // namespace occsim
