// occtune as a user meets it: a whole session on a small scenario (real headless runs, a few
// seconds), its files, and what `occsim --culling` makes of its tuned.json; bad input ends with
// one line and exit code 2 before any run; a fit that does not converge writes no tuned.json;
// Ctrl-C leaves the sample log whole and --resume finishes the session.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "occsim/culling/registry/plugin_loader.h"
#include "occsim/culling/registry/registry.h"
#include "shell_command.h"
#include "sim/output/plots.h"
#include "sim/output/report.h"
#include "sim/output/version.h"
#include "tune/measure.h"
#include "tune/options.h"
#include "tune/parameters.h"
#include "tune/report.h"
#include "tune/sample_log.h"
#include "tune/tuned_file.h"

extern char** environ;

namespace occsim::tune {
namespace {

namespace fs = std::filesystem;

const std::string kSmall = std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";

using occsim::testing::Outcome;
using occsim::testing::shell;

Outcome run(const std::string& exe, const std::string& args) { return shell(exe + " " + args); }

Outcome occtune(const std::string& args) { return run(OCCTUNE_EXE, args); }

// Per process: other checkouts run the same suites on this machine.
fs::path tempDir(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("occtune-test-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(p);
    return p;
}

size_t lineCount(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

std::vector<std::string> lines(const fs::path& file) {
    std::ifstream in(file);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

std::string text(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// One parameter keeps the smallest budget small (a quadratic in one parameter: 3 terms, 5
// samples); 12 frames (7 timed after the scenario's 5 warm-up) keep every run short.
const std::string kQuick = " --params base_time --budget 5 --batch 3 --frames 12 --repetitions 1";

// Whether a session finished: exit 0 (tuned.json: accepted or no change) or kExitRejected
// (tuned.rejected.json). Which of them depends on measured frame times, so on the machine's load:
// a test of anything but the verdict takes either (the verdict's rules have tests of their own
// on given ratios, tests/tune/test_confirm.cpp).
bool finished(const Outcome& o) { return o.exit_code == 0 || o.exit_code == kExitRejected; }
fs::path tunedFileIn(const fs::path& dir) {
    return fs::exists(dir / "tuned.json") ? dir / "tuned.json" : dir / "tuned.rejected.json";
}

TEST(Occtune, ASessionOnASmallScenarioWritesEveryFileAndOccsimReadsTheTunedValues) {
    const fs::path dir = tempDir("session");
    const Outcome o = occtune(kSmall + kQuick + " --out " + dir.string());
    ASSERT_TRUE(finished(o)) << o.output;
    // The verdict is on the console.
    EXPECT_TRUE(o.output.find("verdict: accepted: ") != std::string::npos ||
                o.output.find("verdict: no change: ") != std::string::npos ||
                o.output.find("verdict: REJECTED: ") != std::string::npos)
        << o.output;

    // tuned.json (or tuned.rejected.json): the scenario's culling form, the tuned value within
    // its bounds.
    const fs::path tuned_file = tunedFileIn(dir);
    const nlohmann::json tuned = nlohmann::json::parse(text(tuned_file));
    EXPECT_EQ(tuned["format_version"], 1);
    EXPECT_EQ(tuned["culling"]["algorithm"], "statistical");
    const double base_time = tuned["culling"]["statistical"]["base_time"].get<double>();
    EXPECT_GE(base_time, 0.05);
    EXPECT_LE(base_time, 2.0);
    EXPECT_EQ(tuned["culling"]["statistical"]["decay_a"].get<double>(),
              2.0);  // not tuned: the paper's

    // The sample log: settings, then two batches (two references and 3, then 2 samples).
    const std::vector<std::string> log = lines(dir / "samples.jsonl");
    ASSERT_EQ(log.size(), 1u + 5u + 4u);
    size_t samples = 0, references = 0;
    for (size_t i = 1; i < log.size(); ++i) {
        const nlohmann::json line = nlohmann::json::parse(log[i]);
        (line["kind"] == "reference" ? references : samples) += 1;
        EXPECT_EQ(line["error_pixels"], 0) << "the statistical culler is conservative";
        EXPECT_EQ(line["frames"].size(), 7u);
    }
    EXPECT_EQ(samples, 5u);
    EXPECT_EQ(references, 4u);

    const nlohmann::json cost = nlohmann::json::parse(text(dir / "cost_model.json"));
    for (const char* key :
         {"query_ms", "triangle_ms", "draw_ms", "constant_ms", "residual_rms_ms"}) {
        EXPECT_TRUE(cost[key].is_number()) << key;
        EXPECT_GE(cost[key].get<double>(), 0.0) << key;
    }

    // confirmation.json: the report's confirmation as numbers, agreeing with tuned.json.
    const nlohmann::json conf = nlohmann::json::parse(text(dir / "confirmation.json"));
    EXPECT_EQ(conf["culler"], "statistical");
    ASSERT_EQ(conf["parameters"].size(), 1u);
    EXPECT_EQ(conf["parameters"][0]["name"], "base_time");
    if (conf["verdict"] == "accepted") {  // "no change" writes the reference into tuned.json
        EXPECT_DOUBLE_EQ(conf["parameters"][0]["tuned"].get<double>(), base_time);
    }
    EXPECT_DOUBLE_EQ(conf["parameters"][0]["reference"].get<double>(), 2.0 / 3.0);
    ASSERT_EQ(conf["variants"].size(), 2u);
    EXPECT_EQ(conf["variants"][0]["variant"], "fitted (seed 7)");
    EXPECT_EQ(conf["variants"][1]["variant"], "held out (seed 8)");
    for (const nlohmann::json& v : conf["variants"]) {
        EXPECT_GT(v["mean_ratio"]["median"].get<double>(), 0.0);
        EXPECT_LE(v["mean_ratio"]["min"].get<double>(), v["mean_ratio"]["max"].get<double>());
        EXPECT_EQ(v["tuned_error_pixels"], 0);
    }
    EXPECT_TRUE(conf["verdict"] == "accepted" || conf["verdict"] == "no change" ||
                conf["verdict"] == "REJECTED")
        << conf["verdict"];

    const std::string report = text(dir / "report.md");
    for (const char* part : {"## Choice", "## Confirmation", "Measurement noise", "fitted (seed 7)",
                             "held out (seed 8)", "Residual RMS", "Leave-one-out prediction error",
                             "Prediction error on runs left out", "Ceres Solver Report",
                             "| 0 / 0 |", "held out: seed 8 changes the layout of the scene"}) {
        EXPECT_NE(report.find(part), std::string::npos) << part;
    }
    if (findOnPath("gnuplot")) {
        EXPECT_TRUE(fs::is_regular_file(dir / "tune-base_time.png"));
        EXPECT_TRUE(fs::is_regular_file(dir / "tune-cost-model.svg"));
    }
    for (const auto& entry : fs::directory_iterator(dir)) {
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
    }

    // occsim runs the scenario with the tuned values.
    const Outcome r = run(OCCSIM_EXE, "run " + kSmall + " --frames 6 --culling " +
                                          tuned_file.string() + " --out " + (dir / "run").string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("statistical"), std::string::npos) << r.output;

    // A second session in the same folder would mix two logs: refused.
    const Outcome again = occtune(kSmall + kQuick + " --out " + dir.string());
    EXPECT_EQ(again.exit_code, 2);
    EXPECT_EQ(lineCount(again.output), 1u) << again.output;
    EXPECT_NE(again.output.find("--resume"), std::string::npos) << again.output;
    fs::remove_all(dir);
}

// A run on a busy machine is said as bench says it of its run: at the end, with how many of the
// session's runs were busy (the test sets the load; it never depends on the machine's).
TEST(Occtune, ABusyMachineIsCountedOverTheSessionAndSaidAtTheEnd) {
    RunMetadata quiet, busy;
    quiet.hardware_threads = busy.hardware_threads = 2;
    quiet.load_before = {0.5, 0.5, 0.5};
    quiet.load_after = {1.9, 1.0, 1.0};
    busy.load_before = {3.5, 3.0, 3.0};
    busy.load_after = {4.1, 3.0, 3.0};
    SessionRuns session;
    EXPECT_FALSE(noteMachineLoad(session, quiet));
    EXPECT_TRUE(noteMachineLoad(session, busy));
    EXPECT_TRUE(noteMachineLoad(session, busy));
    EXPECT_NE(busyMachineLine(busy).find("busy machine: other work ran beside this run"),
              std::string::npos);
    EXPECT_EQ(busyMachineLine(quiet), "");
    EXPECT_EQ(session.runs, 3u);
    EXPECT_EQ(session.busy_runs, 2u);
    TuneResult r;
    r.hardware_threads = 2;
    EXPECT_EQ(busyMachineNote(r), "");
    r.runs = session.runs;
    r.busy_runs = session.busy_runs;
    EXPECT_EQ(busyMachineNote(r).rfind("busy machine: 2 of 3 runs of this session ran beside "
                                       "other work",
                                       0),
              0u)
        << busyMachineNote(r);
}

TEST(Occtune, VersionPrintsTheSameVersionAndCommitAsOccsim) {
    const Outcome tune = occtune("--version");
    ASSERT_EQ(tune.exit_code, 0) << tune.output;
    EXPECT_EQ(tune.output, versionLine("occtune") + "\n");
    EXPECT_EQ(tune.output.rfind(std::string("occtune ") + OCCSIM_PROJECT_VERSION + " (commit ", 0),
              0u)
        << tune.output;
    const Outcome sim = run(OCCSIM_EXE, "--version");
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
    EXPECT_EQ(sim.output, versionLine("occsim") + "\n");
}

// A scene warning is said once a session, not once for every batch and confirmation run that
// builds the scene again: here a city whose one small block has more lots than fit a building
// (the held-out variant's other seed may give another count, said once too).
TEST(Occtune, ASessionPrintsEachSceneWarningOnce) {
    const fs::path dir = tempDir("warnings");
    fs::create_directories(dir);
    nlohmann::json city = nlohmann::json::parse(
        text(std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/city-small.json"));
    city["name"] = "city-warning";
    city["scene"]["sources"][0].update(
        {{"blocks_x", 1}, {"blocks_z", 1}, {"block_size", 10}, {"buildings_per_block", 64}});
    city.erase("expect");
    const fs::path scenario = dir / "city-warning.json";
    std::ofstream(scenario) << city.dump(1);

    const Outcome o = occtune(scenario.string() + kQuick + " --out " + (dir / "out").string());
    // Warnings come before any fit: a fit that does not converge on noisy timings (exit 1) says
    // them too.
    ASSERT_TRUE(finished(o) || o.exit_code == kExitFitFailed) << o.output;
    std::istringstream out(o.output);
    std::vector<std::string> warnings;
    for (std::string line; std::getline(out, line);) {
        if (line.rfind("warning: ", 0) == 0) warnings.push_back(line);
    }
    ASSERT_FALSE(warnings.empty()) << "the scene must warn of its small lots:\n" << o.output;
    EXPECT_NE(warnings.front().find("lots were too small for a building"), std::string::npos)
        << warnings.front();
    for (size_t i = 0; i < warnings.size(); ++i) {
        for (size_t k = i + 1; k < warnings.size(); ++k) {
            EXPECT_NE(warnings[i], warnings[k]) << "said twice in one session:\n" << o.output;
        }
    }
    fs::remove_all(dir);
}

TEST(Occtune, BadInputIsOneLineWithExitCode2BeforeAnyRun) {
    const fs::path dir = tempDir("bad");
    fs::create_directories(dir);
    const fs::path malformed = dir / "bad.json";
    std::ofstream(malformed) << "{\"format_version\": 1, \"frames\": 0}\n";
    const fs::path out = dir / "out";
    struct Case {
        std::string args, expected;
    };
    const std::vector<Case> cases = {
        {kSmall + " --bounds base_time=1:1", "empty range"},
        {kSmall + " --bounds base_time=2:0.5", "inverted range"},
        {kSmall + " --bounds decay_b=0:2",
         "decay_b=2 is not a valid setting: expected a value in [0, 1]"},
        {kSmall + " --algo fastest", "--algo: unknown algorithm 'fastest'"},
        {kSmall + " --algo vfc", "--algo vfc: its options descriptor marks no option tunable"},
        {kSmall + " --algo statistical+ --params base_time",
         "unknown parameter 'base_time' of statistical+"},
        {kSmall + " --plugin /no/such/libplugin.so",
         "--plugin /no/such/libplugin.so: no such file"},
        {kSmall + " --params speed", "unknown parameter 'speed'"},
        {kSmall + " --params base_time --bounds decay_a=1:3", "not tuned"},
        {kSmall + " --budget 11", "--budget 11: too small for the model"},
        {kSmall + " --params base_time --budget 4", "needs at least 5 samples"},
        {kSmall + " --frames 5", "warm-up frames"},
        {kSmall + " --objective median", "--objective"},
        {kSmall + " --resume", "no sample log"},
        {"/no/such/scenario.json", "/no/such/scenario.json"},
        {malformed.string(), "/frames"},
        {kSmall + " --frmaes 3", "--frmaes"},
        {kSmall + " --backend vulkan", "--backend: expected auto, egl or osmesa, got 'vulkan'"},
        {kSmall + " --device 50", "--device 50: out of range"},
    };
    for (const Case& c : cases) {
        const Outcome o = occtune(c.args + " --out " + out.string());
        EXPECT_EQ(o.exit_code, 2) << c.args << "\n" << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << c.args << "\n" << o.output;
        EXPECT_NE(o.output.find(c.expected), std::string::npos) << c.args << "\n" << o.output;
        EXPECT_FALSE(fs::exists(out)) << c.args;
    }
    fs::remove_all(dir);
}

// A complete log made here, so that --resume goes straight to the fits.
void writeSyntheticLog(const fs::path& dir) {
    LogSettings s;
    s.scenario_file = kSmall;
    s.scenario_name = "teapots-small";
    s.scenario_hash = textHash(text(kSmall));
    s.parameters = {"base_time"};
    s.bounds = {{0.05, 2.0}};
    s.frames = 12;
    s.warmup_frames = 5;
    s.seed = 1;
    s.initial_samples = 5;
    fs::create_directories(dir);
    SampleLog log(dir / "samples.jsonl", s);
    std::vector<LoggedRun> batch = {{0, true, {2.0 / 3.0}, 30.0, 40.0, 0, {}}};
    for (int i = 0; i < 5; ++i) {
        LoggedRun r{0, false, {0.1 + 0.4 * i}, 30.0 + i, 40.0 + i, 0, {}};
        for (int f = 0; f < 7; ++f)
            r.frames.push_back({20.0 + f + i, 10.0 * f, 1e5 + 1e4 * i, 100.0 + f, 1.0 * i});
        batch.push_back(r);
    }
    batch[0].frames = batch[1].frames;
    log.appendBatch(batch);
}

TEST(Occtune, AFitThatDoesNotConvergeIsReportedWithCeresSummaryAndWritesNoTunedJson) {
    const fs::path dir = tempDir("noconv");
    writeSyntheticLog(dir);
    const Outcome o =
        occtune(kSmall + kQuick + " --resume --max-fit-iterations 1 --out " + dir.string());
    EXPECT_EQ(o.exit_code, 1) << o.output;
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("did not converge"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("Ceres Solver Report"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("NO_CONVERGENCE"), std::string::npos) << o.output;
    EXPECT_FALSE(fs::exists(dir / "tuned.json"));
    fs::remove_all(dir);
}

TEST(Occtune, ResumeRefusesALogWrittenForOtherSettings) {
    const fs::path dir = tempDir("mismatch");
    writeSyntheticLog(dir);
    const Outcome o = occtune(
        kSmall +
        " --params base_time --budget 5 --frames 12 --bounds base_time=0.1:1 --resume --out " +
        dir.string());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(lineCount(o.output), 1u) << o.output;
    EXPECT_NE(o.output.find("--bounds base_time=0.05:2"), std::string::npos) << o.output;
    fs::remove_all(dir);
}

// Starts occtune with its output going to `output`; returns its pid.
pid_t spawnOcctune(const std::vector<std::string>& args, const fs::path& output) {
    std::vector<std::string> argv_text = {OCCTUNE_EXE};
    argv_text.insert(argv_text.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_text) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = -1;
    posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    return pid;
}

TEST(Occtune, CtrlCKeepsTheLogWholeWritesNoTunedJsonAndResumeFinishes) {
    const fs::path dir = tempDir("interrupt");
    fs::create_directories(dir);
    // 40 frames per run, so that a batch lasts long enough (seconds) for the signal to land in one.
    const std::vector<std::string> args = {kSmall,
                                           "--params",
                                           "base_time",
                                           "--budget",
                                           "6",
                                           "--batch",
                                           "2",
                                           "--frames",
                                           "40",
                                           "--repetitions",
                                           "1",
                                           "--out",
                                           (dir / "out").string()};
    const pid_t pid = spawnOcctune(args, dir / "output.txt");
    ASSERT_GT(pid, 0);
    // Wait (no wall-clock assertion: only a generous limit against a hang) for the first batch
    // in the log, then interrupt the second.
    const fs::path log_file = dir / "out" / "samples.jsonl";
    for (int i = 0; i < 6000 && lines(log_file).size() < 4; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_GE(lines(log_file).size(), 4u) << text(dir / "output.txt");
    ::kill(pid, SIGINT);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    const std::string said = text(dir / "output.txt");
    EXPECT_EQ(lineCount(said), 1u) << said;
    EXPECT_NE(said.find("interrupted"), std::string::npos) << said;
    EXPECT_NE(said.find("--resume"), std::string::npos) << said;
    EXPECT_FALSE(fs::exists(dir / "out" / "tuned.json"));
    // Whole: every line is JSON, and it reads as a sample log.
    for (const std::string& line : lines(log_file))
        EXPECT_TRUE(nlohmann::json::accept(line)) << line;
    const size_t logged = SampleLog::read(log_file).samples().size();
    EXPECT_GE(logged, 2u);
    EXPECT_LT(logged, 6u);

    std::string command;
    for (const std::string& a : args) command += " " + a;
    const Outcome o = occtune(command + " --resume");
    // Finished: the whole budget logged and a verdict written, whichever (finished()).
    EXPECT_TRUE(finished(o)) << o.output;
    EXPECT_EQ(SampleLog::read(log_file).samples().size(), 6u);
    EXPECT_TRUE(fs::exists(tunedFileIn(dir / "out")));
    EXPECT_NE(o.output.find("verdict: "), std::string::npos) << o.output;
    fs::remove_all(dir);
}

// SIGTERM (a batch system's stop) is the same request as Ctrl-C, with its own exit status.
TEST(Occtune, SigtermKeepsTheLogWholeAndSaysHowToResume) {
    const fs::path dir = tempDir("sigterm");
    fs::create_directories(dir);
    const pid_t pid =
        spawnOcctune({kSmall, "--params", "base_time", "--budget", "6", "--batch", "2", "--frames",
                      "40", "--repetitions", "1", "--out", (dir / "out").string()},
                     dir / "output.txt");
    ASSERT_GT(pid, 0);
    const fs::path log_file = dir / "out" / "samples.jsonl";
    for (int i = 0; i < 6000 && lines(log_file).size() < 4; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_GE(lines(log_file).size(), 4u) << text(dir / "output.txt");
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << text(dir / "output.txt");
    EXPECT_EQ(WEXITSTATUS(status), 143);
    const std::string said = text(dir / "output.txt");
    EXPECT_NE(said.find("interrupted"), std::string::npos) << said;
    EXPECT_NE(said.find("--resume"), std::string::npos) << said;
    EXPECT_FALSE(fs::exists(dir / "out" / "tuned.json"));
    fs::remove_all(dir);
}

// ---- a "no change" tuned.json changes no decision ------------------------------------------

// Per frame of `algorithm`'s configuration in `occsim bench`'s frames.csv: "queries objects_drawn".
std::vector<std::string> decisionsPerFrame(const fs::path& frames_csv) {
    const std::vector<std::string> rows = lines(frames_csv);
    if (rows.empty()) return {};
    std::vector<std::string> header;
    std::istringstream head(rows[0]);
    for (std::string cell; std::getline(head, cell, ',');) header.push_back(cell);
    const auto column = [&](const std::string& name) {
        return static_cast<size_t>(std::find(header.begin(), header.end(), name) - header.begin());
    };
    const size_t frame = column("frame"), queries = column("queries"),
                 objects = column("objects_drawn");
    std::vector<std::string> out;
    for (size_t i = 1; i < rows.size(); ++i) {
        std::vector<std::string> cells;
        std::istringstream row(rows[i]);
        for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
        if (cells.size() < header.size()) continue;
        out.push_back(cells[frame] + ": " + cells[queries] + " queries, " + cells[objects] +
                      " drawn");
    }
    return out;
}

// occsim bench in deterministic-latency mode (counts reproducible), with a culling file or none.
std::vector<std::string> benchDecisions(const std::string& algorithm, const std::string& plugin,
                                        const fs::path& culling, const fs::path& out) {
    std::string args = "bench " + kSmall + " --algos " + algorithm +
                       " --deterministic-latency 8 --frames 10 --out " + out.string();
    if (!plugin.empty()) args += " --plugin " + plugin;
    if (!culling.empty()) args += " --culling " + culling.string();
    const Outcome o = run(OCCSIM_EXE, args);
    EXPECT_EQ(o.exit_code, 0) << args << "\n" << o.output;
    return decisionsPerFrame(out / "frames.csv");
}

// The issue's case: a session ended "no change" but its tuned.json carried the fitted cost model,
// which changed statistical+'s queries and draws on every run. A "no change" file holds the
// reference setting and no cost model: the same per-frame counts as no file at all, for the
// paper's culler, statistical+ and a plugin's culler.
TEST(Occtune, ANoChangeTunedJsonChangesNoDecision) {
    const std::string plugin = TEST_PLUGIN_GOOD;
    loadPlugin(plugin);  // test-frustum, for the file's read-back through the scenario readers
    const fs::path dir = tempDir("no-change");
    fs::create_directories(dir);
    // A well-fitting cost model (residual 10 % of the mean frame): tunedSetting() confirms with it.
    FrameTimeModelFit cost;
    cost.model = FrameTimeModel{1.0, 0.02, 0.1, 0.01, 1.0};
    cost.fit.converged = true;
    cost.mean_frame_ms = 10.0;
    cost.residual_rms_ms = 1.0;
    for (const std::string name : {"statistical", "statistical+", "test-frustum"}) {
        const CullerRow& algorithm = *findCuller(name);
        const ParameterSpace space = parseParameterSpace(algorithm, "", {});
        const OptionValues defaults(algorithm.options);
        const Setting reference{"paper", space.paper(defaults), std::nullopt};
        std::string why;
        const Setting tuned = tunedSetting(algorithm, defaults, cost, true, &why);
        const Verdict no_change{Verdict::Kind::NoChange, "the same decisions"};
        const fs::path file = dir / (name + "-tuned.json");
        std::ofstream(file)
            << tunedFile(algorithm, writtenSetting(no_change, tuned, reference)).text;

        const std::string with_plugin = name == "test-frustum" ? plugin : "";
        const std::vector<std::string> without =
            benchDecisions(name, with_plugin, {}, dir / (name + "-without"));
        ASSERT_EQ(without.size(), 10u) << name;
        EXPECT_EQ(benchDecisions(name, with_plugin, file, dir / (name + "-with")), without)
            << name << ": " << text(file);
        if (tuned.cost_model) {
            // The file with the cost model (what "no change" wrote before) does change them.
            const fs::path costly = dir / (name + "-costly.json");
            std::ofstream(costly) << tunedFile(algorithm, tuned).text;
            EXPECT_NE(benchDecisions(name, with_plugin, costly, dir / (name + "-costly")), without)
                << name;
        }
    }
    fs::remove_all(dir);
}

// docs/tuning.md holds the descriptors' tunable parameters between two markers: regenerate them
// with `occtune --list-parameters --markdown` when a descriptor changes.
TEST(Occtune, TheParameterTableIsTheDescriptorsOwnOutput) {
    const std::string page = text(std::string(OCCSIM_SOURCE_DIR) + "/docs/tuning.md");
    const std::string begin = "<!-- BEGIN occtune --list-parameters --markdown -->\n";
    const std::string end = "<!-- END occtune --list-parameters --markdown -->";
    const size_t b = page.find(begin), e = page.find(end);
    ASSERT_NE(b, std::string::npos);
    ASSERT_NE(e, std::string::npos);
    const Outcome o = occtune("--list-parameters --markdown");
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_EQ(page.substr(b + begin.size(), e - b - begin.size()), o.output)
        << "docs/tuning.md is out of date: paste the output of occtune --list-parameters "
           "--markdown";
    // statistical+'s three, which are not the paper's culler's.
    for (const char* key : {"queries_before_restart", "requery_parallax", "waits_per_frame"})
        EXPECT_NE(o.output.find("| `statistical+` | `" + std::string(key) + "` |"),
                  std::string::npos)
            << key;
    for (const char* key : {"decay_a", "decay_b"})
        EXPECT_EQ(o.output.find("| `statistical+` | `" + std::string(key) + "` |"),
                  std::string::npos)
            << key;
}

// A tuned.json is one culler's confirmed setting ("tuned_for"): occsim refuses one that names a
// culler not loaded, sets another culler's algorithm or options, holds an option out of its range
// or a cost model not scoped to the culler tuned, in one line naming the file and the JSON
// pointer, with exit code 2 and nothing written.
TEST(Occtune, ATunedJsonThatIsNotOneCullersSettingIsRefusedInOneLine) {
    const fs::path dir = tempDir("bad-tuned");
    fs::create_directories(dir);
    struct Case {
        std::string name, json, expected;
    };
    const std::vector<Case> cases = {
        {"other-algorithm",
         R"({"format_version": 1, "tuned_for": "statistical+", "culling": {"algorithm": "statistical"}})",
         R"(/culling/algorithm: expected "statistical+" (the culler this file was tuned for))"},
        {"not-loaded",
         R"({"format_version": 1, "tuned_for": "gpu-magic", "culling": {"algorithm": "statistical"}})",
         "/tuned_for: expected a loaded culler"},
        {"out-of-range",
         R"({"format_version": 1, "tuned_for": "statistical", "culling": {"algorithm": "statistical", "statistical": {"decay_b": 2}}})",
         "/culling/statistical/decay_b"},
        {"unscoped-cost",
         R"({"format_version": 1, "tuned_for": "statistical+", "culling": {"algorithm": "statistical+", "cost_model": {"query_box_ms": 0.02}}})",
         R"(/culling/cost_model: expected "cullers": ["statistical+"])"},
        {"other-options",
         R"({"format_version": 1, "tuned_for": "statistical", "culling": {"algorithm": "statistical", "chc": {}}})",
         R"(/culling/chc: expected the options of "statistical")"},
        // The approximation knobs every querying culler shares would change the others too.
        {"shared-threshold",
         R"({"format_version": 1, "tuned_for": "statistical", "culling": {"algorithm": "statistical", "threshold_pixels": 4}})",
         R"(/culling/threshold_pixels: a tuned file changes "statistical" (the culler this file was tuned for) alone)"},
        {"shared-stale",
         R"({"format_version": 1, "tuned_for": "statistical", "culling": {"algorithm": "statistical", "stale_results": true}})",
         "/culling/stale_results: a tuned file changes"},
    };
    for (const Case& c : cases) {
        const fs::path file = dir / (c.name + ".json");
        std::ofstream(file) << c.json << "\n";
        const fs::path out = dir / ("out-" + c.name);
        const Outcome o =
            run(OCCSIM_EXE, "bench " + kSmall + " --algos statistical --frames 6 --culling " +
                                file.string() + " --out " + out.string());
        EXPECT_EQ(o.exit_code, 2) << c.name << "\n" << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << c.name << "\n" << o.output;
        EXPECT_NE(o.output.find(file.string()), std::string::npos) << c.name << "\n" << o.output;
        EXPECT_NE(o.output.find(c.expected), std::string::npos) << c.name << "\n" << o.output;
        EXPECT_FALSE(fs::exists(out)) << c.name;
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace occsim::tune
