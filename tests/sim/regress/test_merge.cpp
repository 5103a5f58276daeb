// Merging the shards of a regression run (sim/regress/merge.h) on results made here (no
// rendering): what is joined, in the set's order, and what is refused, naming the file and what
// is wrong. The merge of real runs: test_merge_run.cpp; `occsim merge` as a command:
// tests/system/test_merge.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "merge_files.h"
#include "sim/regress/junit_reader.h"
#include "sim/regress/merge.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using namespace merge_files;

TEST(Merge, JoinsFourShardsInTheOrderOfTheSet) {
    const fs::path root = freshDir("join");
    std::vector<fs::path> dirs;
    for (uint32_t i : {2u, 0u, 3u, 1u}) dirs.push_back(writeShard(root, i, 4));
    const MergedRun run = mergeShards(dirs);
    EXPECT_EQ(run.report.table(), wholeReport().table());
    EXPECT_EQ(checksTsv(run.report), checksTsv(wholeReport()));
    EXPECT_EQ(run.shard_of, (std::vector<uint32_t>{0, 1, 2, 3, 0, 1}));
    EXPECT_FALSE(run.report.passed());
    writeMergedReport(root / "merged", run);
    const auto suites = readJunit(root / "merged/junit.xml");
    EXPECT_EQ(suites.size(), 6u);
    const std::string md = readFile(root / "merged/report.md");
    EXPECT_NE(md.find(wholeReport().table()), std::string::npos) << md;
    EXPECT_NE(md.find("| 3/4 |"), std::string::npos) << md;
    const auto summary = nlohmann::json::parse(readFile(root / "merged/summary.json"));
    EXPECT_EQ(summary["totals"]["scenarios"], 6);
    EXPECT_EQ(summary["totals"]["failed_checks"], 1);
}

TEST(Merge, RefusesAMissingShard) {
    const fs::path root = freshDir("missing");
    const std::string e =
        mergeError({writeShard(root, 0, 4), writeShard(root, 1, 4), writeShard(root, 3, 4)});
    EXPECT_NE(e.find("shard(s) 2 of 4 missing"), std::string::npos) << e;
}

TEST(Merge, RefusesAShardThatRanTwice) {
    const fs::path root = freshDir("twice");
    const fs::path a = writeShard(root, 1, 2);
    fs::copy(a, root / "again");
    const std::string e = mergeError({writeShard(root, 0, 2), a, root / "again"});
    EXPECT_NE(e.find("again/shard.json: /shard: shard 1/2 ran twice"), std::string::npos) << e;
}

TEST(Merge, RefusesAShardFromAnotherScenarioSet) {
    const fs::path root = freshDir("otherset");
    ScenarioSet other = sixScenarios();
    other.id = "fedcba9876543210";
    const std::string e =
        mergeError({writeShard(root / "x", 0, 2), writeShard(root / "y", 1, 2, other)});
    EXPECT_NE(
        e.find(
            "y/shard-1/shard.json: /scenario_set: from another scenario set (id fedcba9876543210"),
        std::string::npos)
        << e;
    // Shards of a different count are of another run too.
    const std::string f = mergeError({writeShard(root / "z", 0, 2), writeShard(root / "w", 1, 3)});
    EXPECT_NE(f.find("w/shard-1/shard.json: /shard: shard 1/3, but"), std::string::npos) << f;
}

TEST(Merge, RefusesTwoShardsClaimingTheSameScenario) {
    const fs::path root = freshDir("claimed");
    const fs::path s0 = writeShard(root, 0, 2), s1 = writeShard(root, 1, 2);
    // Shard 1 also claims a.json, which shard 0 ran.
    ShardResult r = readShardResult(s1);
    r.report.scenarios.push_back(outcomeOf("scenarios/a.json"));
    writeShardResult(s1, r);
    const std::string e = mergeError({s0, s1});
    EXPECT_NE(e.find("shard-1/shard.json: /scenarios: scenarios/a.json is also claimed by"),
              std::string::npos)
        << e;
}

// A scenario that ran and whose summary.json is gone would leave the merged summary unseen.
TEST(Merge, RefusesAScenarioThatRanWithoutItsSummary) {
    const fs::path root = freshDir("nosummary");
    const fs::path s0 = writeShard(root, 0, 2), s1 = writeShard(root, 1, 2);
    EXPECT_EQ(mergeError({s0, s1}), "");
    EXPECT_EQ(mergeShards({s0, s1}).summaries[3]["scenario"]["name"], "d");
    fs::remove(s1 / "d" / "summary.json");
    const std::string e = mergeError({s0, s1});
    EXPECT_NE(e.find("shard-1/d/summary.json: missing; scenarios/d.json ran in this shard"),
              std::string::npos)
        << e;
    // A skipped scenario (e) has none to miss.
    EXPECT_FALSE(fs::exists(s0 / "e"));
}

// A summary.json copied from another scenario's folder would file its figures under this one.
TEST(Merge, RefusesASummaryThatBelongsToAnotherScenario) {
    const fs::path root = freshDir("copied");
    const fs::path s0 = writeShard(root, 0, 2), s1 = writeShard(root, 1, 2);
    fs::copy_file(s0 / "a" / "summary.json", s1 / "b" / "summary.json",
                  fs::copy_options::overwrite_existing);
    const std::string e = mergeError({s0, s1});
    EXPECT_NE(e.find("shard-1/b/summary.json: /scenario: the summary of scenario 'a' (id a, "
                     "file scenarios/a.json); expected that of 'b' (id b, file scenarios/b.json)"),
              std::string::npos)
        << e;
    // A run's own summary (no id: `occsim run --out` into a regress folder) is not the scenario's.
    writeFile(s1 / "b" / "summary.json",
              R"({"scenario": {"name": "b", "file": "scenarios/b.json"}})");
    EXPECT_NE(mergeError({s0, s1}).find("(id (none)"), std::string::npos) << mergeError({s0, s1});
}

// Two files whose names are each other's: a.json named "b", b.json named "a". Each is filed
// under its own id, the folder regress wrote it to, never under the other's.
TEST(Merge, ScenariosNamedAsEachOthersFilesAreFiledUnderTheirOwnIds) {
    const fs::path root = freshDir("swapped");
    ScenarioSet set;
    set.id = "feedfacefeedface";
    set.scenarios = {"scenarios/a.json", "scenarios/b.json"};
    set.ids = {"a", "b"};
    ShardResult r;
    r.set = set;
    for (size_t k = 0; k < 2; ++k) {
        ScenarioOutcome o;
        o.scenario = set.scenarios[k];
        o.id = set.ids[k];
        o.name = k == 0 ? "b" : "a";
        o.checks.push_back({"zero error pixels: chc", "0 on every frame", "0", true});
        r.report.scenarios.push_back(o);
        fs::create_directories(root / "shard" / o.id);
        writeFile(root / "shard" / o.id / "summary.json", summaryOf(o));
    }
    writeShardResult(root / "shard", r);
    const MergedRun run = mergeShards({root / "shard"});
    ASSERT_EQ(run.summaries.size(), 2u);
    EXPECT_EQ(run.report.scenarios[0].id, "a");
    EXPECT_EQ(run.summaries[0]["scenario"]["file"], "scenarios/a.json");
    EXPECT_EQ(run.summaries[0]["scenario"]["name"], "b");
    EXPECT_EQ(run.summaries[1]["scenario"]["file"], "scenarios/b.json");
    // Swapped back into each other's folders, as the old merge read them: refused.
    fs::rename(root / "shard" / "a", root / "shard" / "tmp");
    fs::rename(root / "shard" / "b", root / "shard" / "a");
    fs::rename(root / "shard" / "tmp", root / "shard" / "b");
    EXPECT_NE(mergeError({root / "shard"}).find("/scenario: the summary of scenario 'a' (id b"),
              std::string::npos)
        << mergeError({root / "shard"});
}

// A history series is one machine and backend: shards rendered elsewhere are merged apart.
TEST(Merge, RefusesShardsRenderedOnDifferentBackendsOrCpus) {
    const fs::path root = freshDir("backends");
    const fs::path s0 = writeShard(root, 0, 2), s1 = writeShard(root, 1, 2);
    auto withMachine = [&](const fs::path& shard, const std::string& id,
                           const std::string& backend) {
        Json summary = Json::parse(readFile(shard / id / "summary.json"));
        summary["machine"] = {{"backend", backend}, {"gl_renderer", "llvmpipe"}};
        writeFile(shard / id / "summary.json", summary.dump());
    };
    withMachine(s0, "a", "egl");
    withMachine(s1, "b", "egl");
    EXPECT_EQ(mergeError({s0, s1}), "");
    withMachine(s1, "d", "osmesa");
    const std::string e = mergeError({s0, s1});
    EXPECT_NE(e.find("scenarios/d.json was rendered on osmesa, llvmpipe but scenarios/a.json on "
                     "egl, llvmpipe"),
              std::string::npos)
        << e;
    withMachine(s1, "d", "egl");
    ShardResult other = readShardResult(s1);
    other.cpu = "Another CPU";
    writeShardResult(s1, other);
    EXPECT_NE(mergeError({s0, s1}).find("/machine/cpu: Another CPU"), std::string::npos)
        << mergeError({s0, s1});
}

TEST(Merge, RefusesATruncatedOrDisagreeingJunitFile) {
    const fs::path root = freshDir("junit");
    const fs::path s0 = writeShard(root, 0, 2), s1 = writeShard(root, 1, 2);
    const std::string xml = readFile(s1 / "junit.xml");
    writeFile(s1 / "junit.xml", xml.substr(0, xml.size() / 2));
    const std::string e = mergeError({s0, s1});
    EXPECT_NE(e.find("shard-1/junit.xml: line "), std::string::npos) << e;
    EXPECT_NE(e.find("truncated or corrupt"), std::string::npos) << e;
    // Whole, but not the file shard.json describes (another shard's).
    fs::copy_file(s0 / "junit.xml", s1 / "junit.xml", fs::copy_options::overwrite_existing);
    const std::string f = mergeError({s0, s1});
    EXPECT_NE(f.find("shard-1/junit.xml: testsuite 1 ('a'"), std::string::npos) << f;
}

}  // namespace
}  // namespace occsim
