// Stopped is not lost: SIGINT or SIGTERM ends run, bench and regress after the frame in hand with
// the whole frames written, marked partial, and one line saying so; a culler that throws is named
// with its frame and the frames before it are kept; one that crashes is named with its frame.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "signalled_run.h"

namespace {

using occsim::testing::runAndSignal;
using occsim::testing::SignalledRun;
namespace fs = std::filesystem;

const std::string kSmall = std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";
// Far more frames than a run reaches before the signal: it is always stopped mid-run.
const std::string kManyFrames = "20000";

fs::path tempDir(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("occsim-stopping-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

std::string text(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

size_t lineCount(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

fs::path plugin(const std::string& kind) {
    return fs::path(TEST_PLUGIN_DIR) / ("libtest_plugin_" + kind + ".so");
}

// The partial summary.json of a run of `configurations` stopped after some whole frames: every
// configuration has exactly those frames, in summary.json and frames.csv alike.
uint32_t expectWholeFrames(const fs::path& out, size_t configurations) {
    const nlohmann::json summary = nlohmann::json::parse(text(out / "summary.json"));
    EXPECT_TRUE(summary["partial"].is_object()) << summary.dump(2);
    const uint32_t reached = summary["partial"]["frames_reached"].get<uint32_t>();
    EXPECT_EQ(summary["algorithms"].size(), configurations);
    for (const auto& a : summary["algorithms"]) EXPECT_EQ(a["frames"], reached) << a.dump();
    EXPECT_EQ(lineCount(text(out / "frames.csv")), 1 + configurations * reached);
    const std::string report = text(out / "report.md");
    EXPECT_NE(report.find("**partial: "), std::string::npos) << report;
    return reached;
}

// The first progress line ("frame N/M ...") shows frames are done: then the signal comes.
TEST(Stopping, ASignalEndsRunAndBenchAfterTheFrameInHandWithTheFramesWrittenMarkedPartial) {
    const struct {
        std::string command;
        std::vector<std::string> algos;
        int signal;
        std::string name;
    } cases[] = {{"bench", {"--algos", "vfc,statistical"}, SIGINT, "SIGINT"},
                 {"run", {"--algo", "chc"}, SIGTERM, "SIGTERM"}};
    for (const auto& c : cases) {
        const fs::path dir = tempDir(c.command);
        std::vector<std::string> argv = {OCCSIM_EXE,
                                         c.command,
                                         kSmall,
                                         "--frames",
                                         kManyFrames,
                                         "--out",
                                         (dir / "out").string()};
        argv.insert(argv.end(), c.algos.begin(), c.algos.end());
        const SignalledRun r =
            runAndSignal(argv, "frame ", c.signal, (dir / "stdout.txt").string());
        ASSERT_TRUE(r.signal_sent) << r.terminal;
        ASSERT_TRUE(r.exited) << "ended by signal " << r.ended_by << ": " << r.terminal;
        EXPECT_EQ(r.exit_code, 128 + c.signal) << r.terminal;  // as a shell reports it
        const std::string line =
            "occsim " + c.command + ": partial: interrupted by " + c.name + " after ";
        EXPECT_NE(r.terminal.find(line), std::string::npos) << r.terminal;
        EXPECT_NE(r.terminal.find("(marked partial); run the same command again"),
                  std::string::npos)
            << r.terminal;
        const uint32_t reached = expectWholeFrames(dir / "out", c.algos[0] == "--algos" ? 2 : 1);
        EXPECT_GE(reached, 1u);
        EXPECT_LT(reached, 20000u);
        const nlohmann::json summary = nlohmann::json::parse(text(dir / "out/summary.json"));
        EXPECT_EQ(summary["partial"]["signal"], c.name);
        // The console's table came before the line.
        EXPECT_NE(text(dir / "stdout.txt").find("partial: interrupted by"), std::string::npos);
        fs::remove_all(dir);
    }
}

TEST(Stopping, ACullerThatThrowsIsNamedWithItsFrameAndTheFramesBeforeItAreKept) {
    const fs::path dir = tempDir("throws");
    const SignalledRun r = runAndSignal(
        {OCCSIM_EXE, "bench", kSmall, "--plugin", plugin("failing").string(), "--algos",
         "vfc,test-frustum", "--frames", "10", "--out", (dir / "out").string()},
        "", 0, (dir / "stdout.txt").string());
    ASSERT_TRUE(r.exited) << r.terminal;
    EXPECT_EQ(r.exit_code, 1) << r.terminal;
    EXPECT_NE(r.terminal.find("occsim bench: partial: configuration 'test-frustum' failed at "
                              "frame 3: out of budget after 3 of 10 frames"),
              std::string::npos)
        << r.terminal;
    EXPECT_EQ(expectWholeFrames(dir / "out", 2), 3u);
    const nlohmann::json summary = nlohmann::json::parse(text(dir / "out/summary.json"));
    EXPECT_TRUE(summary["partial"]["signal"].is_null());
    fs::remove_all(dir);
}

// A crash cannot be saved from, but its line names the culler to blame; the signal still ends
// the process as it would have without the handler.
TEST(Stopping, ACullerThatCrashesIsNamedWithItsFrame) {
    const fs::path dir = tempDir("crashes");
    const SignalledRun r = runAndSignal(
        {OCCSIM_EXE, "bench", kSmall, "--plugin", plugin("crashing").string(), "--algos",
         "vfc,test-frustum", "--frames", "10", "--out", (dir / "out").string()},
        "", 0, (dir / "stdout.txt").string());
    EXPECT_FALSE(r.exited) << r.terminal;
    EXPECT_EQ(r.ended_by, SIGSEGV) << r.terminal;
    EXPECT_NE(r.terminal.find("occsim: crashed (SIGSEGV) in configuration 'test-frustum' at "
                              "frame 3"),
              std::string::npos)
        << r.terminal;
    fs::remove_all(dir);
}

// A stopped regress fails the scenario in hand ("every frame run") instead of checking or
// updating a baseline against half a run, writes its partial outputs and shard result, and
// appends nothing to the history.
TEST(Stopping, ASignalEndsRegressWithThePartialScenarioFailedAndNoHistory) {
    const fs::path dir = tempDir("regress");
    nlohmann::json scenario = nlohmann::json::parse(text(kSmall));
    scenario["name"] = "long-teapots";
    scenario["frames"] = std::stoi(kManyFrames);
    scenario["expect"] = {{"algorithms", {"vfc"}}, {"deterministic_latency", 8}};
    std::ofstream(dir / "long-teapots.json") << scenario.dump(2);
    const fs::path out = dir / "out";
    const SignalledRun r =
        runAndSignal({OCCSIM_EXE, "regress", (dir / "long-teapots.json").string(), "--out",
                      out.string(), "--history", (dir / "history").string()},
                     "[1/1]", SIGINT, (dir / "stdout.txt").string());
    ASSERT_TRUE(r.signal_sent) << r.terminal;
    ASSERT_TRUE(r.exited) << r.terminal;
    EXPECT_EQ(r.exit_code, 130) << r.terminal;
    EXPECT_NE(r.terminal.find("occsim regress: interrupted by SIGINT in "), std::string::npos)
        << r.terminal;
    EXPECT_NE(r.terminal.find("1 of 1 scenarios ran, the last one partly"), std::string::npos)
        << r.terminal;
    expectWholeFrames(out / "long-teapots", 1);
    EXPECT_NE(text(out / "shard.json").find("every frame run"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "history")) << "a stopped run's figures are no history";
    EXPECT_FALSE(fs::exists(dir / "long-teapots.baseline.json"));
    fs::remove_all(dir);
}

}  // namespace
