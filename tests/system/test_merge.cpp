// Merging the shards of a regression run, and the history of runs, on results made here (no
// rendering): what is joined, what is refused (one line, exit 2, nothing overwritten), what a
// history report plots and flags.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>

#include "merge_files.h"
#include "sim/regress/junit_reader.h"
#include "sim/regress/merge.h"
#include "sim/regress/result_files.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using namespace merge_files;

// Six scenarios a..f; scenario c fails one check, e is skipped.
ScenarioSet sixScenarios() {
    ScenarioSet set;
    set.id = "0123456789abcdef";
    for (const char* n : {"a", "b", "c", "d", "e", "f"}) {
        set.scenarios.push_back(std::string("scenarios/") + n + ".json");
        set.ids.push_back(n);
    }
    return set;
}

ScenarioOutcome outcomeOf(const std::string& file) {
    ScenarioOutcome o;
    o.scenario = file;
    o.id = o.name = fs::path(file).stem().string();
    if (o.name == "e") {
        o.skipped = true;
        o.note = "no expect block";
        return o;
    }
    o.checks.push_back({"zero error pixels: chc", "0 on every frame", "0 (3 tie px)", true});
    o.checks.push_back({"queries per frame = baseline: chc", "identical over 3 frames",
                        o.name == "c" ? "frame 1: 7 <b>&\"" : "identical over 3 frames",
                        o.name != "c"});
    o.seconds = 0.25;
    return o;
}

// A scenario's summary.json as runRegression writes it: its scenario block names it.
std::string summaryOf(const ScenarioOutcome& o) {
    return Json{{"scenario", {{"id", o.id}, {"name", o.name}, {"file", o.scenario}}}}.dump() + "\n";
}

// Shard i of n of the six, as `occsim regress --shard i/n --out dir` leaves it.
fs::path writeShard(const fs::path& root, uint32_t i, uint32_t n,
                    const ScenarioSet& set = sixScenarios()) {
    ShardResult r;
    r.set = set;
    r.shard = {i, n};
    for (size_t k = i; k < set.scenarios.size(); k += n)
        r.report.scenarios.push_back(outcomeOf(set.scenarios[k]));
    const fs::path dir = root / ("shard-" + std::to_string(i));
    writeShardResult(dir, r);
    // Every scenario that ran leaves its summary.json (runRegression's writeRunOutputs).
    for (const ScenarioOutcome& o : r.report.scenarios) {
        if (!o.ran()) continue;
        fs::create_directories(dir / o.id);
        writeFile(dir / o.id / "summary.json", summaryOf(o));
    }
    return dir;
}

RegressReport wholeReport() {
    RegressReport report;
    for (const auto& f : sixScenarios().scenarios) report.scenarios.push_back(outcomeOf(f));
    return report;
}

std::string mergeError(const std::vector<fs::path>& dirs) {
    try {
        mergeShards(dirs);
    } catch (const ResultFileError& e) {
        return e.what();
    }
    return "";
}

TEST(Junit, ReadsBackWhatJunitXmlWrites) {
    const auto suites = parseJunit(junitXml(wholeReport()), "x.xml");
    ASSERT_EQ(suites.size(), 6u);
    EXPECT_EQ(suites[2].name, "c");
    EXPECT_EQ(suites[2].testcases, 2u);
    EXPECT_EQ(suites[2].failures, 1u);
    EXPECT_EQ(suites[4].skipped, 1u);
}

// A failed check's entry names the pictures of its own culler's worst frame, not another's; the
// culler a check is about survives a shard's file, so a merged junit.xml says the same.
TEST(Junit, AFailedChecksEntryListsOnlyItsOwnCullersPictures) {
    ShardResult r;
    r.set = sixScenarios();
    r.set.scenarios = {"scenarios/a.json"};
    r.set.ids = {"a"};
    r.shard = {0, 1};
    ScenarioOutcome o = outcomeOf("scenarios/a.json");
    o.checks = {
        {"zero error pixels: statistical", "0 on every frame", "4 px", false, "statistical"},
        {"zero error pixels: statistical+", "0 on every frame", "9 px", false, "statistical+"},
        {"frame time chc / vfc", "<= 1.00", "1.20", false}};
    o.captures = {"out/a/worst-error-statistical-frame-00003.png",
                  "out/a/worst-error-statistical+-frame-00007.png"};
    r.report.scenarios = {o};
    auto failureOf = [](const std::string& xml, const std::string& check) {
        const size_t at = xml.find("name=\"" + check + "\"><failure");
        EXPECT_NE(at, std::string::npos) << check << " in " << xml;
        return xml.substr(at, xml.find("</failure>", at) - at);
    };
    for (const RegressReport& report : {r.report, [&] {
                                            const fs::path dir = freshDir("junit-pictures");
                                            writeShardResult(dir / "shard", r);
                                            return readShardResult(dir / "shard").report;
                                        }()}) {
        const std::string xml = junitXml(report);
        const std::string plain = failureOf(xml, "zero error pixels: statistical");
        EXPECT_NE(plain.find("worst-error-statistical-frame-00003.png"), std::string::npos);
        EXPECT_EQ(plain.find("worst-error-statistical+-frame"), std::string::npos) << plain;
        const std::string plus = failureOf(xml, "zero error pixels: statistical+");
        EXPECT_NE(plus.find("worst-error-statistical+-frame-00007.png"), std::string::npos);
        EXPECT_EQ(plus.find("worst-error-statistical-frame"), std::string::npos) << plus;
        EXPECT_EQ(failureOf(xml, "frame time chc / vfc").find("capture:"), std::string::npos);
    }
}

TEST(Junit, EveryTruncationOfAFileIsRefusedNamingTheFile) {
    const std::string xml = junitXml(wholeReport());
    for (size_t cut = 0; cut + 1 < xml.size(); cut += 7) {
        EXPECT_THROW(
            {
                try {
                    parseJunit(xml.substr(0, cut), "cut.xml");
                } catch (const ResultFileError& e) {
                    EXPECT_EQ(std::string(e.what()).rfind("cut.xml: line ", 0), 0u) << e.what();
                    throw;
                }
            },
            ResultFileError)
            << "cut at " << cut;
    }
    std::string edited = xml;
    edited.replace(edited.find("<testcase"), 9, "<testcaze");
    EXPECT_THROW(parseJunit(edited, "edited.xml"), ResultFileError);
}

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

// A name with a control character is written so that junit.xml stays well-formed XML, and reads
// back as the merge compares it.
TEST(Junit, AControlCharacterInANameKeepsTheFileWellFormed) {
    RegressReport report = wholeReport();
    report.scenarios[0].name =
        "a\x01"
        "b\tc";
    report.scenarios[0].checks[0].got = "bell\x07";
    const std::string xml = junitXml(report);
    EXPECT_EQ(xml.find('\x01'), std::string::npos);
    EXPECT_EQ(xml.find('\x07'), std::string::npos);
    const auto suites = parseJunit(xml, "x.xml");
    EXPECT_EQ(suites[0].name,
              "a\\x01"
              "b\tc");
    EXPECT_EQ(suites[0].name, junitVisibleText(report.scenarios[0].name));
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
