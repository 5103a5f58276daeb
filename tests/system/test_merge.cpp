// Merging the shards of a regression run, and the history of runs, on results made here (no
// rendering): what is joined, what is refused (one line, exit 2, nothing overwritten), what a
// history report plots and flags.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/regress/history.h"
#include "sim/regress/history_plot.h"
#include "sim/regress/history_report.h"
#include "sim/regress/junit_reader.h"
#include "sim/regress/merge.h"
#include "sim/regress/result_files.h"
#include "sim/regress/shard_result.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("occsim-merge-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string readFile(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeFile(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

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

struct Command {
    int status = -1;
    std::string output;  // stdout and stderr
};

Command runOccsim(const std::string& args) {
    const std::string command = std::string(OCCSIM_EXE) + " " + args + " 2>&1";
    Command c;
    FILE* pipe = popen(command.c_str(), "r");
    std::array<char, 4096> buf{};
    while (fgets(buf.data(), buf.size(), pipe)) c.output += buf.data();
    const int status = pclose(pipe);
    c.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return c;
}

// The command refuses with one line naming `expected`, exit 2, and `out` is as it was.
void expectRefused(const std::string& args, const std::string& expected, const fs::path& out) {
    const std::string before = readFile(out / "report.md");
    const Command c = runOccsim(args);
    EXPECT_EQ(c.status, 2) << c.output;
    EXPECT_EQ(std::count(c.output.begin(), c.output.end(), '\n'), 1) << c.output;
    EXPECT_NE(c.output.find(expected), std::string::npos) << c.output;
    EXPECT_EQ(readFile(out / "report.md"), before) << "the earlier report was overwritten";
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

// A history entry of machine `host`, with statistical's speedup and queries in scenario s.
HistoryEntry entry(const std::string& date, const std::string& host, double speedup,
                   double queries = 40) {
    HistoryEntry e;
    e.commit = "c0ffee" + date.substr(8, 2);
    e.date = date;
    e.hostname = host;
    e.cpu = "Test CPU";
    e.renderer = "llvmpipe";
    e.backend = "egl";
    e.scenarios["s"]["vfc"] = {1.0, 0, 120, 0};
    e.scenarios["s"]["statistical"] = {speedup, queries, 60, 0};
    e.scenarios["t"]["statistical"] = {2.0, 10, 20, 0};
    return e;
}

fs::path historyOf(const std::string& name, const std::vector<HistoryEntry>& entries) {
    const fs::path dir = freshDir(name);
    for (const HistoryEntry& e : entries) appendHistory(dir / "history", e);
    return dir / "history";
}

HistoryOptions windowOf(size_t n) {
    HistoryOptions o;
    o.window = n;
    return o;
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

TEST(History, AnEntryReadsBackAsWritten) {
    const fs::path dir = historyOf("roundtrip", {entry("2025-01-01T00:00:00Z", "m", 2.5)});
    const auto runs = readHistory(dir);
    ASSERT_EQ(runs.size(), 1u);
    EXPECT_EQ(historyEntryJson(runs[0]), historyEntryJson(entry("2025-01-01T00:00:00Z", "m", 2.5)));
    EXPECT_EQ(runs[0].scenarios.at("s").at("statistical").speedup, 2.5);
}

TEST(History, AnEntryMadeNowRecordsMachineCommitAndFigures) {
    const Json summary =
        Json::parse(R"json({"machine": {"backend": "osmesa", "gl_renderer": "llvmpipe (LLVM 15)"},
        "algorithms": [{"configuration": "vfc", "speedup_over_vfc": 1.0, "queries_per_frame": 0,
                        "objects_per_frame": 100, "error": {"pixels_per_frame_mean": 0}},
                       {"configuration": "chc", "speedup_over_vfc": 1.8, "queries_per_frame": 12.5,
                        "objects_per_frame": 30, "error": {"pixels_per_frame_mean": 0.5}}]})json");
    const HistoryEntry e = historyEntryNow({{"s", summary}}, "abc123");
    EXPECT_EQ(e.commit, "abc123");
    EXPECT_EQ(e.backend, "osmesa");
    EXPECT_EQ(e.renderer, "llvmpipe (LLVM 15)");
    EXPECT_FALSE(e.hostname.empty());
    EXPECT_FALSE(e.cpu.empty());
    EXPECT_EQ(e.date.size(), 20u) << e.date;
    EXPECT_EQ(e.scenarios.at("s").at("chc").speedup, 1.8);
    EXPECT_EQ(e.scenarios.at("s").at("chc").queries, 12.5);
    EXPECT_EQ(e.scenarios.at("s").at("chc").error, 0.5);
}

TEST(History, AnotherFormatVersionIsRefusedOneLineExitTwoNothingWritten) {
    const fs::path dir = historyOf("version", {entry("2025-01-01T00:00:00Z", "m", 2.5)});
    std::string text = historyEntryJson(entry("2025-01-02T00:00:00Z", "m", 2.5));
    text.replace(text.find("\"version\": 1"), 12, "\"version\": 2");
    writeFile(dir / "v2.json", text);
    EXPECT_THROW(readHistory(dir), ResultFileError);
    const size_t files = std::distance(fs::directory_iterator(dir), fs::directory_iterator());
    const fs::path out = dir.parent_path() / "report";
    fs::create_directories(out);
    writeFile(out / "report.md", "earlier report\n");
    writeFile(out / ".occsim-run", "");  // an earlier report's folder, replaceable
    expectRefused("history " + dir.string() + " --out " + out.string(),
                  "v2.json: /version: history format version 2; this program reads version 1", out);
    // regress --history refuses before running anything: no result folder, no new entry.
    const fs::path regress_out = dir.parent_path() / "regress-out";
    expectRefused(std::string("regress ") + OCCSIM_SOURCE_DIR +
                      "/scenarios/small/teapots-small.json --out " + regress_out.string() +
                      " --history " + dir.string(),
                  "history format version 2", out);
    EXPECT_FALSE(fs::exists(regress_out));
    EXPECT_EQ(
        static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator())),
        files);
}

TEST(HistoryReport, ThreeRunsArePlottedAndAnInjectedSlowdownIsFlagged) {
    const fs::path dir = historyOf("slowdown", {entry("2025-01-01T00:00:00Z", "m", 2.00),
                                                entry("2025-01-02T00:00:00Z", "m", 2.05),
                                                entry("2025-01-03T00:00:00Z", "m", 1.40)});
    const HistoryAnalysis a = analyseHistory(readHistory(dir), windowOf(1));
    ASSERT_EQ(a.runs.size(), 3u);
    ASSERT_EQ(a.flagged.size(), 1u);
    EXPECT_EQ(a.flagged[0].scenario, "s");
    EXPECT_EQ(a.flagged[0].algorithm, "statistical");
    EXPECT_EQ(a.flagged[0].figure, "speedup over VFC");
    EXPECT_TRUE(a.flagged[0].worse);
    EXPECT_NE(a.flagged[0].text().find("2.050 -> 1.400"), std::string::npos) << a.flagged[0].text();

    const fs::path out = dir.parent_path() / "report";
    const auto files = writeHistoryReport(out, a, windowOf(1));
    EXPECT_EQ(files, (std::vector<std::string>{"history-s.svg", "history-t.svg", "report.md"}));
    const std::string md = readFile(out / "report.md");
    EXPECT_NE(md.find("- **s statistical: speedup over VFC 2.050 -> 1.400"), std::string::npos)
        << md;
    EXPECT_NE(md.find("![s](history-s.svg)"), std::string::npos) << md;
    const std::string svg = readFile(out / "history-s.svg");
    // Four panels, two algorithms (one line each) and three runs per line; the slowdown ringed.
    size_t lines = 0, points = 0, pos = 0;
    while ((pos = svg.find("<polyline class=\"line\"", pos)) != std::string::npos) ++lines, ++pos;
    pos = 0;
    while ((pos = svg.find("<circle class=\"point\"", pos)) != std::string::npos) ++points, ++pos;
    EXPECT_EQ(lines, 8u);
    EXPECT_EQ(points, 24u);
    EXPECT_EQ(svg.find("class=\"flagged\""), svg.rfind("class=\"flagged\"")) << "one ring";
    EXPECT_NE(svg.find("class=\"flagged\""), std::string::npos);
    EXPECT_NE(svg.find("run 3, statistical: 1.4"), std::string::npos);
}

TEST(HistoryReport, RunsWithinTheSpreadAreNotFlagged) {
    const fs::path dir = historyOf("steady", {entry("2025-01-01T00:00:00Z", "m", 2.00),
                                              entry("2025-01-02T00:00:00Z", "m", 2.05),
                                              entry("2025-01-03T00:00:00Z", "m", 2.02)});
    const HistoryAnalysis a = analyseHistory(readHistory(dir), windowOf(1));
    EXPECT_TRUE(a.flagged.empty()) << a.flagged.front().text();
    EXPECT_NE(
        historyMarkdown(a, windowOf(1)).find("## Changes beyond the run-to-run spread\n\nNone."),
        std::string::npos);
    // Too few runs for the window: said, not flagged.
    const HistoryAnalysis b = analyseHistory(readHistory(dir), windowOf(3));
    EXPECT_TRUE(b.flagged.empty());
    ASSERT_EQ(b.not_compared.size(), 1u);
    EXPECT_NE(b.not_compared[0].find("3 runs, 6 needed for a window of 3"), std::string::npos)
        << b.not_compared[0];
}

TEST(HistoryReport, FailOnChangeFailsOnWorseOnlyNeverOnBetter) {
    // A speedup that rose beyond the spread is flagged "better": printed, and exit 0.
    const fs::path dir = historyOf("faster", {entry("2025-01-01T00:00:00Z", "m", 2.00),
                                              entry("2025-01-02T00:00:00Z", "m", 2.05),
                                              entry("2025-01-03T00:00:00Z", "m", 2.90)});
    const HistoryAnalysis a = analyseHistory(readHistory(dir), windowOf(1));
    ASSERT_EQ(a.flagged.size(), 1u);
    EXPECT_FALSE(a.flagged[0].worse);
    EXPECT_FALSE(a.anyWorse());
    const std::string out = (dir.parent_path() / "r").string();
    const Command better =
        runOccsim("history " + dir.string() + " --out " + out + " --window 1 --fail-on-change");
    EXPECT_EQ(better.status, 0) << better.output;
    EXPECT_NE(better.output.find("changed: s statistical: speedup over VFC 2.050 -> 2.900 "
                                 "(+41.5%, better)"),
              std::string::npos)
        << better.output;
    // The same folder with a slowdown after it: worse, exit 1.
    appendHistory(dir, entry("2025-01-04T00:00:00Z", "m", 1.20));
    const HistoryAnalysis b = analyseHistory(readHistory(dir), windowOf(1));
    EXPECT_TRUE(b.anyWorse());
    const Command worse =
        runOccsim("history " + dir.string() + " --out " + out + " --window 1 --fail-on-change");
    EXPECT_EQ(worse.status, 1) << worse.output;
    EXPECT_NE(worse.output.find(", worse)"), std::string::npos) << worse.output;
}

TEST(HistoryReport, MachinesAreSeparateSeriesNeverMixed) {
    // Machine m is steady at 2.0; a slower machine n joins with 1.0. Mixed into one series that
    // would read as a slowdown.
    const fs::path dir = historyOf(
        "machines",
        {entry("2025-01-01T00:00:00Z", "m", 2.0), entry("2025-01-02T00:00:00Z", "m", 2.0),
         entry("2025-01-03T00:00:00Z", "m", 2.0), entry("2025-01-04T00:00:00Z", "n", 1.0)});
    const HistoryAnalysis a = analyseHistory(readHistory(dir), windowOf(1));
    EXPECT_EQ(a.series.size(), 2u);
    EXPECT_TRUE(a.flagged.empty()) << a.flagged.front().text();
    const std::string svg = historySvg(a, "s");
    EXPECT_NE(svg.find("data-algorithm=\"statistical\" data-series=\"2\""), std::string::npos);
    // Through the command: the same report, exit 0, and a flagged slowdown with --fail-on-change.
    const Command c = runOccsim("history " + dir.string() + " --out " +
                                (dir.parent_path() / "r").string() + " --window 1");
    EXPECT_EQ(c.status, 0) << c.output;
    EXPECT_NE(c.output.find("history: 4 runs, 2 series, 2 scenarios, 0 changes flagged"),
              std::string::npos)
        << c.output;
    appendHistory(dir, entry("2025-01-05T00:00:00Z", "m", 1.5));
    const Command d =
        runOccsim("history " + dir.string() + " --out " + (dir.parent_path() / "r").string() +
                  " --window 1 --fail-on-change");
    EXPECT_EQ(d.status, 1) << d.output;
    EXPECT_NE(d.output.find("changed: s statistical: speedup over VFC 2.000 -> 1.500"),
              std::string::npos)
        << d.output;
}

}  // namespace
}  // namespace occsim
