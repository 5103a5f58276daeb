// `occsim merge` and `occsim regress` as commands on results made here (no rendering): bad input
// is one line, exit 2, and nothing overwritten or run. The merge itself:
// tests/sim/regress/test_merge.cpp.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>

#include "merge_commands.h"
#include "sim/regress/junit_reader.h"
#include "sim/regress/merge.h"
#include "sim/regress/result_files.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using namespace merge_files;

TEST(MergeCommand, BadInputIsOneLineExitTwoAndNothingOverwritten) {
    const fs::path root = freshDir("cli");
    const fs::path s0 = writeShard(root, 0, 2), s1 = writeShard(root, 1, 2);
    const fs::path out = root / "merged";
    const std::string shards = s0.string() + " " + s1.string();
    const Command good = runOccsim("merge " + shards + " --out " + out.string());
    EXPECT_EQ(good.status, 1) << good.output;  // scenario c failed a check
    EXPECT_NE(good.output.find("merge: 6 scenarios from 2 shards, 1 failed, 1 skipped"),
              std::string::npos)
        << good.output;
    ASSERT_TRUE(fs::exists(out / "report.md"));

    expectRefused("merge " + s0.string() + " --out " + out.string(), "shard(s) 1 of 2 missing",
                  out);
    expectRefused("merge " + shards + " " + s1.string() + " --out " + out.string(), "ran twice",
                  out);
    expectRefused("merge " + shards + " --out " + s0.string(), "is the shard folder", out);
    ScenarioSet other = sixScenarios();
    other.scenarios.pop_back();
    other.ids.pop_back();
    const fs::path foreign = writeShard(root / "foreign", 1, 2, other);
    expectRefused("merge " + s0.string() + " " + foreign.string() + " --out " + out.string(),
                  "from another scenario set", out);
    ShardResult claimed = readShardResult(s1);
    claimed.report.scenarios.push_back(outcomeOf("scenarios/a.json"));
    writeShardResult(root / "claimed", claimed);
    expectRefused(
        "merge " + s0.string() + " " + (root / "claimed").string() + " --out " + out.string(),
        "is also claimed by", out);
    fs::remove(s0 / "a" / "summary.json");
    expectRefused("merge " + shards + " --out " + out.string(), "a/summary.json: missing", out);
    writeFile(s0 / "a" / "summary.json", "{}\n");
    const std::string xml = readFile(s1 / "junit.xml");
    writeFile(s1 / "junit.xml", xml.substr(0, xml.size() - 20));
    expectRefused("merge " + shards + " --out " + out.string(), "junit.xml: line ", out);
    writeFile(s1 / "junit.xml", "<html>not junit</html>\n");
    expectRefused("merge " + shards + " --out " + out.string(),
                  "junit.xml: line 1: unexpected element <html>", out);
}

// The regress command refuses a set's problems before any work, one line each as every other
// error ("occsim: ..."), exit 2; and an --out that would hold its own inputs.
TEST(RegressCommand, EveryProblemOfTheSetIsItsOwnLineAndNothingRuns) {
    const fs::path root = freshDir("regress-plan");
    const fs::path set = root / "set";
    fs::create_directories(set);
    Json scenario =
        Json::parse(readFile(fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json"));
    scenario["expect"]["baseline"] = "self.json";
    writeFile(set / "self.json", scenario.dump());
    scenario["expect"]["baseline"] = "../x.json";
    writeFile(set / "up.json", scenario.dump());
    const Command c = runOccsim("regress " + set.string() + " --out " + (root / "out").string());
    EXPECT_EQ(c.status, 2) << c.output;
    EXPECT_EQ(std::count(c.output.begin(), c.output.end(), '\n'), 2) << c.output;
    EXPECT_EQ(c.output.rfind("occsim: ", 0), 0u) << c.output;
    EXPECT_NE(c.output.find("\noccsim: "), std::string::npos) << c.output;
    EXPECT_FALSE(fs::exists(root / "out"));

    const Command inside = runOccsim("regress " + set.string() + " --out " + set.string());
    EXPECT_EQ(inside.status, 2) << inside.output;
    EXPECT_NE(inside.output.find("holds the scenario folder"), std::string::npos) << inside.output;
    writeFile(root / "file", "a file\n");
    const Command junit =
        runOccsim("regress " + set.string() + " --out " + (root / "out").string() + " --junit " +
                  (root / "file" / "x.xml").string());
    EXPECT_EQ(junit.status, 2) << junit.output;
    EXPECT_NE(junit.output.find("--junit"), std::string::npos) << junit.output;
    EXPECT_FALSE(fs::exists(root / "out"));
}

// merge and history write only where an occsim output may be replaced: another folder's files
// are never touched.
TEST(MergeCommand, AnOutFolderOfSomeoneElsesIsRefusedAndLeftAsItWas) {
    const fs::path root = freshDir("not-ours");
    const fs::path s0 = writeShard(root, 0, 2), s1 = writeShard(root, 1, 2);
    const fs::path mine = root / "my-notes";
    fs::create_directories(mine);
    writeFile(mine / "report.md", "my own report\n");
    const Command merge =
        runOccsim("merge " + s0.string() + " " + s1.string() + " --out " + mine.string());
    EXPECT_EQ(merge.status, 2) << merge.output;
    EXPECT_EQ(std::count(merge.output.begin(), merge.output.end(), '\n'), 1) << merge.output;
    EXPECT_NE(merge.output.find("--out"), std::string::npos) << merge.output;
    EXPECT_EQ(readFile(mine / "report.md"), "my own report\n");
    EXPECT_FALSE(fs::exists(mine / "summary.json"));

    appendHistory(root / "history", entry("2025-01-01T00:00:00Z", "m", 2.0));
    const Command history =
        runOccsim("history " + (root / "history").string() + " --out " + mine.string());
    EXPECT_EQ(history.status, 2) << history.output;
    EXPECT_EQ(readFile(mine / "report.md"), "my own report\n");
    // An empty folder, or one an earlier occsim run wrote, is replaced as a whole.
    const Command fresh = runOccsim("history " + (root / "history").string() + " --out " +
                                    (root / "report").string());
    EXPECT_EQ(fresh.status, 0) << fresh.output;
    EXPECT_TRUE(fs::exists(root / "report" / ".occsim-run"));
    const Command again = runOccsim("history " + (root / "history").string() + " --out " +
                                    (root / "report").string());
    EXPECT_EQ(again.status, 0) << again.output;
}

TEST(MergeCommand, AJunitOrHistoryThatCannotBeWrittenIsFoundBeforeAnyWork) {
    const fs::path root = freshDir("unwritable");
    const fs::path s0 = writeShard(root, 0, 2), s1 = writeShard(root, 1, 2);
    writeFile(root / "file", "a file\n");
    const std::string shards = s0.string() + " " + s1.string();
    const Command junit = runOccsim("merge " + shards + " --out " + (root / "m").string() +
                                    " --junit " + (root / "file" / "junit.xml").string());
    EXPECT_EQ(junit.status, 2) << junit.output;
    EXPECT_NE(junit.output.find("--junit"), std::string::npos) << junit.output;
    EXPECT_FALSE(fs::exists(root / "m"));
    const Command history = runOccsim("merge " + shards + " --out " + (root / "m").string() +
                                      " --history " + (root / "file").string());
    EXPECT_EQ(history.status, 2) << history.output;
    EXPECT_FALSE(fs::exists(root / "m"));
}

}  // namespace
}  // namespace occsim
