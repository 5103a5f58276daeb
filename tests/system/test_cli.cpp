// The occsim executable as a user meets it: bad input ends with one line and exit code 2, good
// input writes whole files.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"

using namespace occsim::cli_run;

namespace {

TEST(Cli, UnknownAlgorithmIsOneLineNamingTheFlagAndTheChoicesWithExitCode2) {
    const Outcome o =
        runOccsim("run " + kSmall + " --algo fastest --out " + tempPath("a").string());
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("--algo"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("statistical"), std::string::npos) << o.output;
    EXPECT_FALSE(std::filesystem::exists(tempPath("a")));
}

TEST(Cli, MissingScenarioFileNamesTheFileWithExitCode2) {
    const Outcome o = runOccsim("bench /no/such/scenario.json");
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("/no/such/scenario.json"), std::string::npos) << o.output;
}

TEST(Cli, MalformedScenarioNamesFileAndPlaceWithExitCode2AndWritesNothing) {
    const auto dir = tempPath("bad");
    std::filesystem::create_directories(dir);
    const auto file = dir / "bad.json";
    std::ofstream(file) << "{\n  \"format_version\": 1,\n  \"frames\": 0\n}\n";
    const auto out = dir / "out";
    const Outcome o = runOccsim("run " + file.string() + " --out " + out.string());
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("bad.json"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("/frames"), std::string::npos) << o.output;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, BadFlagsAreOneLineWithExitCode2) {
    const std::vector<std::string> cases = {"bench " + kSmall + " --frames 0",
                                            "bench " + kSmall + " --frmaes 3",
                                            "run " + kSmall + " --frames ten", "fly " + kSmall, ""};
    for (const std::string& args : cases) {
        const Outcome o = runOccsim(args);
        EXPECT_EQ(o.exit_code, 2) << args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << args << ": " << o.output;
    }
}

// What a new user tried: each answer names the flag or command and what was expected.
TEST(Cli, BadValuesSayWhatWasExpectedAndWhatWasGiven) {
    const struct {
        std::string args, must_contain;
    } cases[] = {
        {"frobnicate " + kSmall, "unknown command 'frobnicate'; expected one of: run, bench"},
        {"run " + kSmall + " --frames abc",
         "--frames: expected an integer in [1, 10000000], got 'abc'"},
        {"run " + kSmall + " --capture 1,x",
         "--capture: expected an integer in [0, 9999999], got 'x'"},
        {"run " + kSmall + " --capture 40",
         "--capture: frame 40 is past the last frame (40 frames"},
        {"run " + kSmall + " --birds-eye 40", "--birds-eye: frame 40 is past the last frame"},
        {"bench " + kSmall + " --repetitions 0", "--repetitions: expected an integer in [1, 1000]"},
        {"bench " + kSmall + " --frame-order random",
         "--frame-order: expected balanced, rotated or fixed, got 'random'"},
    };
    for (const auto& c : cases) {
        const Outcome o = runOccsim(c.args);
        EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << c.args << ": " << o.output;
        EXPECT_NE(o.output.find(c.must_contain), std::string::npos) << c.args << ": " << o.output;
    }
}

// A run whose every frame is warm-up has no timing to report: it says so instead of 0.00 ms.
TEST(Cli, ARunWithOnlyWarmupFramesSaysNothingWasTimed) {
    const Outcome o = runOccsim("bench " + kSmall + " --algos vfc --frames 3 --out " +
                                tempPath("warmup").string());
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("nothing was timed"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("not timed"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("0.00"), std::string::npos) << o.output;
}

// The first answer fits a terminal (issue 56): bench prints the compact table and the verdict in
// lines of at most 100 columns, the kind of each row, the fastest conservative culler or the tie,
// the wrong pixels and the why command; --wide prints the full table of every figure instead.
TEST(Cli, BenchPrintsACompactTableAndAVerdictThatFitAndWidePrintsEveryFigure) {
    const std::string args =
        "bench " + kSmall +
        " --error --algos vfc,chc,statistical+,async,masked,ideal --frames 30 --out ";
    const Outcome o = runOccsim(args + tempPath("compact").string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    // stderr too: masked's occluder pass says that the teapot has no inscribed occluder mesh.
    EXPECT_NE(o.output.find("\nnote: mesh 0 (of 'teapot 0'"), std::string::npos) << o.output;
    std::istringstream lines(o.output);
    size_t checked = 0;
    for (std::string line; std::getline(lines, line);) {
        EXPECT_LE(line.size(), 100u) << "'" << line << "'";
        ++checked;
    }
    EXPECT_GT(checked, 10u) << o.output;
    // The header's columns, in order.
    const size_t header_at = o.output.find("\nconfiguration  kind ");
    ASSERT_NE(header_at, std::string::npos) << o.output;
    const std::string header =
        o.output.substr(header_at + 1, o.output.find('\n', header_at + 1) - header_at - 1);
    size_t at = 0;
    for (const char* column :
         {"mean ms", "vs vfc", "vs ideal", "queries", "objects", "err px", "missed"}) {
        at = header.find(column, at);
        EXPECT_NE(at, std::string::npos) << column << " in " << header;
    }
    for (const char* part : {"\nvfc ", " cons ", " approx ", " oracle ", "\nverdict: fastest ",
                             "\nwrong pixels: ", "\nwhy "}) {
        EXPECT_NE(o.output.find(part), std::string::npos) << part << " in " << o.output;
    }
    EXPECT_EQ(o.output.find("median ms"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find('\033'), std::string::npos) << "no colour in a pipe: " << o.output;

    const Outcome wide = runOccsim(args + tempPath("wide").string() + " --wide");
    ASSERT_EQ(wide.exit_code, 0) << wide.output;
    for (const char* part :
         {"configuration  mean ms  median ms  p95 ms  gpu ms  queries/fr", "err px/fr", "tie px",
          "pop max", "overdrawn/fr", "speedup", "vs ideal  pareto"}) {
        EXPECT_NE(wide.output.find(part), std::string::npos) << part << " in " << wide.output;
    }
    EXPECT_EQ(wide.output.find("verdict:"), std::string::npos) << wide.output;
}

// On a terminal (script(1) gives the run one) the verdict is coloured; NO_COLOR and TERM=dumb
// turn that off, as a pipe does (above).
TEST(Cli, BenchColoursItsVerdictOnATerminalOnly) {
    const std::string bench = std::string(OCCSIM_EXE) + " bench " + kSmall +
                              " --algos vfc,chc --frames 14 --out " + tempPath("tty").string();
    const Outcome tty = shell("TERM=xterm script -qec '" + bench + "' /dev/null");
    ASSERT_EQ(tty.exit_code, 0) << tty.output;
    EXPECT_NE(tty.output.find("\033[1mverdict:\033[0m "), std::string::npos) << tty.output;
    for (const char* off : {"NO_COLOR=1 TERM=xterm", "TERM=dumb"}) {
        const Outcome plain = shell(std::string(off) + " script -qec '" + bench + "' /dev/null");
        ASSERT_EQ(plain.exit_code, 0) << plain.output;
        EXPECT_NE(plain.output.find("verdict: "), std::string::npos) << off << plain.output;
        EXPECT_EQ(plain.output.find('\033'), std::string::npos) << off << plain.output;
    }
}

TEST(Cli, RunWritesTheSummaryTableAndBothFiles) {
    const auto out = tempPath("ok");
    const Outcome o =
        runOccsim("run " + kSmall + " --algo statistical --frames 5 --error --out " + out.string());
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("statistical"), std::string::npos) << o.output;
    EXPECT_TRUE(std::filesystem::exists(out / "frames.csv"));
    EXPECT_TRUE(std::filesystem::exists(out / "summary.json"));
}

// The console says what the run cost beside its frames: without --error that no ground truth
// was rendered, with it how many renders and what they took.
TEST(Cli, RunStatesItsWallClockAgainstFrameTimeAndWhatGroundTruthCost) {
    const Outcome plain =
        runOccsim("run " + kSmall + " --algo chc --frames 5 --out " + tempPath("plain").string());
    EXPECT_EQ(plain.exit_code, 0) << plain.output;
    EXPECT_NE(plain.output.find("ms wall clock after set-up for"), std::string::npos)
        << plain.output;
    EXPECT_NE(plain.output.find("no ground truth rendered"), std::string::npos) << plain.output;
    const Outcome measured = runOccsim("run " + kSmall + " --algo chc --frames 5 --error --out " +
                                       tempPath("measured").string());
    EXPECT_EQ(measured.exit_code, 0) << measured.output;
    EXPECT_NE(measured.output.find("ground truth 5 renders"), std::string::npos) << measured.output;
}

TEST(Cli, InfoPrintsTheSceneWithoutRendering) {
    const Outcome o = runOccsim("info " + kSmall);
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("triangles"), std::string::npos) << o.output;
    // What was read about occluders is said (issue 56): the teapots carry no roles.
    EXPECT_NE(o.output.find("\noccluders     300 by size, 0 always, 0 never; 0 with an authored "
                            "occluder mesh\n"),
              std::string::npos)
        << o.output;
    // The courtyards' walls are always occluders (scripts/make_levels.py gives the role).
    const Outcome level =
        runOccsim("info " + std::string(OCCSIM_SOURCE_DIR) + "/scenarios/levels/courtyards.json");
    EXPECT_NE(level.output.find("\noccluders     338 by size, 97 always, 0 never"),
              std::string::npos)
        << level.output;
}

// A run with an occluder pass (masked) says the roles in its header; one without does not.
TEST(Cli, ARunWithAnOccluderPassSaysTheOccluderRoles) {
    const Outcome masked = runOccsim("run " + kSmall + " --algo masked --frames 2 --out " +
                                     tempPath("roles-masked").string());
    ASSERT_EQ(masked.exit_code, 0) << masked.output;
    EXPECT_NE(masked.output.find("\noccluders: 300 by size, 0 always, 0 never;"), std::string::npos)
        << masked.output;
    const Outcome vfc = runOccsim("run " + kSmall + " --algo vfc --frames 2 --out " +
                                  tempPath("roles-vfc").string());
    ASSERT_EQ(vfc.exit_code, 0) << vfc.output;
    EXPECT_EQ(vfc.output.find("occluders:"), std::string::npos) << vfc.output;
}

}  // namespace

// Nonsense on the command line is refused before any work, one line each: a name listed twice
// or an empty one in --algos, an output folder that is a file or empty, a JUnit file that is a
// folder; a misspelt flag gets the nearest one.
TEST(Cli, NonsenseAndUnwritableOutputsAreRefusedBeforeAnyRun) {
    const auto dir = tempPath("nonsense");
    std::filesystem::create_directories(dir);
    const auto file = dir / "a-file";
    std::ofstream(file) << "x";
    const auto out = dir / "out";
    const struct {
        std::string args, expected;
    } cases[] = {
        {"bench " + kSmall + " --algos vfc,chc,vfc --out " + out.string(),
         "--algos: 'vfc' is listed twice"},
        {"bench " + kSmall + " --algos vfc,chc, --out " + out.string(),
         "--algos: an empty algorithm name"},
        {"bench " + kSmall + " --out " + file.string(),
         "--out " + file.string() + ": is a file; expected a folder"},
        {"run " + kSmall + " --out ''", "--out: empty; expected a folder"},
        {"regress " + kSmall + " --junit " + dir.string() + " --out " + out.string(),
         "--junit " + dir.string() + ": is a folder; expected a file name"},
        {"bench " + kSmall + " --frame 3", "not expected: 3 --frame; did you mean '--frames'?"},
    };
    for (const auto& c : cases) {
        const Outcome o = runOccsim(c.args);
        EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << o.output;
        EXPECT_NE(o.output.find(c.expected), std::string::npos) << c.args << ": " << o.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
        EXPECT_FALSE(std::filesystem::exists("out/teapots-small/run-statistical/summary.json.tmp"));
    }
    std::filesystem::remove_all(dir);
}

// A regression run that checks nothing (an empty folder, or scenarios without expect blocks)
// fails with one line saying why, unless --allow-empty says that is expected.
TEST(Cli, RegressWithNothingToCheckFailsUnlessAllowed) {
    const auto dir = tempPath("regress-empty");
    const auto empty = dir / "empty", plain = dir / "plain";
    std::filesystem::create_directories(empty);
    std::filesystem::create_directories(plain);
    std::ifstream in(kSmall);
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    text = text.substr(0, text.find(",\n  \"expect\"")) + "\n}\n";  // the same scenario, no expect
    std::ofstream(plain / "plain.json") << text;
    const std::string out = " --out " + (dir / "out").string();
    for (const auto& [folder, why] : {std::pair{empty, "no scenario file found"},
                                      std::pair{plain, "no scenario found has an expect block"}}) {
        const Outcome o = runOccsim("regress " + folder.string() + out);
        EXPECT_EQ(o.exit_code, 1) << o.output;
        EXPECT_NE(o.output.find("occsim regress: nothing was checked: " + std::string(why)),
                  std::string::npos)
            << o.output;
        const Outcome allowed = runOccsim("regress " + folder.string() + " --allow-empty" + out);
        EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
        EXPECT_EQ(allowed.output.find("nothing was checked"), std::string::npos) << allowed.output;
    }
    std::filesystem::remove_all(dir);
}

// A camera that looks away from every object measures empty frames: the run warns in one line
// and gives no speedup (n/a), in the table, report.md and summary.json.
TEST(Cli, ACameraThatSeesNothingWarnsAndGivesNoSpeedup) {
    const auto dir = tempPath("looks-away");
    std::filesystem::create_directories(dir);
    std::ifstream in(kSmall);
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    // The teapots stand at z in [-60, 0]; this camera at z = 6 looks towards +z.
    const std::string from = "\"target\": [0, 1.5, -20]", to = "\"target\": [0, 2, 40]";
    ASSERT_NE(text.find(from), std::string::npos);
    text.replace(text.find(from), from.size(), to);
    const std::string from2 = "\"target\": [-3, 1.5, -35]";
    ASSERT_NE(text.find(from2), std::string::npos);
    text.replace(text.find(from2), from2.size(), "\"target\": [3, 2.5, 40]");
    const auto scenario = dir / "away.json";
    std::ofstream(scenario) << text;
    const auto out = dir / "out";
    const Outcome o = runOccsim("bench " + scenario.string() +
                                " --algos vfc,chc,ideal --frames 8 --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find("warning: the camera sees no object on any frame"), std::string::npos)
        << o.output;
    EXPECT_EQ(o.output.find("1.00x"), std::string::npos)
        << "no speedup, not even vfc over itself: " << o.output;
    // Nor a ratio of empty frames' times: no worst windows (they printed "1.00x ideal" when the
    // noise rounded so, and this test failed on a loaded machine).
    EXPECT_EQ(o.output.find("worst windows"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("n/a"), std::string::npos) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    EXPECT_NE(json.find("\"nothing_in_view\": true"), std::string::npos) << json;
    EXPECT_EQ(json.find("speedup_over_vfc"), std::string::npos) << json;
    std::ifstream report(out / "report.md");
    const std::string md{std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>()};
    EXPECT_NE(md.find("the camera sees no object on any frame"), std::string::npos) << md;
    std::filesystem::remove_all(dir);
}

// summary.json says what ran and how to run it again: the version and commit, every option of
// every culler after defaults, and the command shell-quoted, which pasted back runs as typed.
TEST(Cli, SummaryJsonRecordsTheVersionTheOptionsAndACommandThatPastesBack) {
    const auto dir = tempPath("repro");
    const auto out = dir / "it's a folder";
    const Outcome o = runOccsim(
        "bench " + kSmall + " --algos vfc,statistical+ --frames 2 --out \"" + out.string() + "\"");
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    EXPECT_NE(json.find("\"occsim\": {\n    \"commit\": \""), std::string::npos) << json;
    EXPECT_NE(json.find("\"version\": \"0."), std::string::npos) << json;
    for (const char* option : {"\"options\": {", "\"base_time\": ", "\"cost_model\": ",
                               "\"threshold_pixels\": 0", "\"frame_order\": \"balanced\""}) {
        EXPECT_NE(json.find(option), std::string::npos) << option << " in " << json;
    }
    std::string quoted = (dir / "it'\\\\''s a folder").string();
    quoted.insert(quoted.begin(), '\'');
    quoted.push_back('\'');
    const size_t at = json.find("\"command\": \"");
    ASSERT_NE(at, std::string::npos) << json;
    const size_t start = at + std::string("\"command\": \"").size();
    std::string command = json.substr(start, json.find("\",\n", start) - start);
    EXPECT_NE(command.find(quoted), std::string::npos) << command << " lacks " << quoted;
    // JSON escapes the backslash of '\'' once: undo that, then run it again from the shell.
    for (size_t p = command.find("\\\\"); p != std::string::npos; p = command.find("\\\\", p + 1))
        command.erase(p, 1);
    std::filesystem::remove_all(out);
    const Outcome again = shell(command);
    EXPECT_EQ(again.exit_code, 0) << command << ": " << again.output;
    EXPECT_TRUE(std::filesystem::exists(out / "summary.json")) << command;
    std::filesystem::remove_all(dir);
}

TEST(Cli, VersionPrintsTheProjectVersionAndCommitThatSummaryJsonRecords) {
    const Outcome v = runOccsim("--version");
    ASSERT_EQ(v.exit_code, 0) << v.output;
    const std::string prefix = std::string("occsim ") + OCCSIM_PROJECT_VERSION + " (commit ";
    ASSERT_EQ(v.output.rfind(prefix, 0), 0u) << v.output;
    ASSERT_EQ(lineCount(v.output), 1u) << v.output;
    const std::string commit = v.output.substr(prefix.size(), v.output.find(")\n") - prefix.size());
    EXPECT_FALSE(commit.empty()) << v.output;
    const auto out = tempPath("version");
    const Outcome o = runOccsim("run " + kSmall + " --algo vfc --frames 1 --out " + out.string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    std::ifstream summary(out / "summary.json");
    const std::string json{std::istreambuf_iterator<char>(summary),
                           std::istreambuf_iterator<char>()};
    EXPECT_NE(json.find("\"commit\": \"" + commit + "\""), std::string::npos) << json;
    EXPECT_NE(json.find(std::string("\"version\": \"") + OCCSIM_PROJECT_VERSION + "\""),
              std::string::npos)
        << json;
    std::filesystem::remove_all(out);
}
