// Plugin cullers through the command lines: a bad plugin file stops every command, and a plugin's
// culler runs wherever a built-in runs (the scenario's options with the same checks, bench
// tables, summaries, baselines and JUnit files). The plugins are built from
// tests/plugins/test_plugin.cpp; the loader's own tests are in test_plugin_loader.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "occsim/culling/registry/plugin_loader.h"
#include "occsim/culling/registry/registry.h"
#include "plugin_files.h"
#include "shell_command.h"

namespace {

using namespace occsim;
using occsim::testing::Outcome;
using occsim::testing::shell;
namespace fs = std::filesystem;
using occsim::testing::lineCount;
using occsim::testing::pluginFile;
using occsim::testing::tempDir;

Outcome occsim(const std::string& args) { return shell(std::string(OCCSIM_EXE) + " " + args); }

std::string text(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// teapots-small with the good plugin named in its "plugins" key and `culling` as its culling
// section.
fs::path scenarioWithPlugin(const fs::path& dir, const nlohmann::json& culling,
                            const nlohmann::json& expect = nullptr) {
    nlohmann::json s = nlohmann::json::parse(
        text(fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json"));
    s["plugins"] = {pluginFile("good").string()};
    s["culling"] = culling;
    s["frames"] = 12;
    s.erase("expect");
    if (!expect.is_null()) s["expect"] = expect;
    const fs::path file = dir / "with-plugin.json";
    std::ofstream(file) << s.dump(2);
    return file;
}

TEST(PluginCli, ABadPluginStopsEveryCommandWithExitCode2AndWritesNothing) {
    const fs::path dir = tempDir("cli-bad");
    const std::string small =
        std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";
    for (const std::string kind :
         {"missing", "no_entry", "other_abi", "taken_name", "bad_descriptor", "throwing"}) {
        const fs::path plugin = kind == "missing" ? dir / "libnope.so" : pluginFile(kind);
        for (const std::string& command : {"run " + small, "bench " + small, "regress " + small}) {
            const Outcome o = occsim(command + " --plugin " + plugin.string() + " --out " +
                                     (dir / "out").string());
            EXPECT_EQ(o.exit_code, 2) << command << " " << kind << ": " << o.output;
            EXPECT_EQ(lineCount(o.output), 1u) << o.output;
            EXPECT_NE(o.output.find("--plugin " + plugin.string() + ": "), std::string::npos)
                << o.output;
            EXPECT_FALSE(fs::exists(dir / "out")) << command << " " << kind;
        }
    }
    fs::remove_all(dir);
}

// A factory that throws only when a run asks for options other than its defaults (the plugin
// loads: its defaults work) is bad input as well, and both executables say so alike: exit code 2,
// the plugin's file and the culler named.
TEST(PluginCli, AFactoryThatThrowsInARunIsExitCode2InOccsimAndOcctune) {
    const fs::path dir = tempDir("cli-picky");
    const std::string picky = pluginFile("picky").string();
    const std::string expected =
        picky + ": culler 'test-frustum': its factory threw: margin is not 1";
    nlohmann::json s = nlohmann::json::parse(
        text(fs::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json"));
    s["plugins"] = {picky};
    s["culling"] = {{"test-frustum", {{"margin", 0.5}}}};
    s["frames"] = 12;
    s.erase("expect");
    const fs::path scenario = dir / "picky.json";
    std::ofstream(scenario) << s.dump(2);

    const Outcome bench = occsim("bench " + scenario.string() + " --algos test-frustum --out " +
                                 (dir / "bench").string());
    EXPECT_EQ(bench.exit_code, 2) << bench.output;
    EXPECT_NE(bench.output.find(expected), std::string::npos) << bench.output;

    // occtune samples margins other than 1 (its reference keeps the default).
    const Outcome tune = shell(std::string(OCCTUNE_EXE) + " " + OCCSIM_SOURCE_DIR +
                               "/scenarios/small/teapots-small.json --plugin " + picky +
                               " --algo test-frustum --params margin --budget 5 --batch 3 "
                               "--frames 12 --repetitions 1 --out " +
                               (dir / "tune").string());
    EXPECT_EQ(tune.exit_code, 2) << tune.output;
    EXPECT_NE(tune.output.find(expected), std::string::npos) << tune.output;
    fs::remove_all(dir);
}

// A culler that needs a capability the run's device lacks is refused before any work: one line
// naming it and the capability, exit code 2, nothing written. The GL device offers conditional
// rendering; an approximating device (a pixel threshold) withholds it.
TEST(PluginCli, ACullerNeedingWhatTheDeviceLacksIsRefusedWithOneLineAndExitCode2) {
    const fs::path dir = tempDir("cli-needs");
    const std::string small =
        std::string(OCCSIM_SOURCE_DIR) + "/scenarios/small/teapots-small.json";
    const std::string plugin = pluginFile("needs_conditional").string();
    const Outcome plain = occsim("bench " + small + " --plugin " + plugin +
                                 " --algos test-frustum --frames 3 --out " + (dir / "a").string());
    EXPECT_EQ(plain.exit_code, 0) << plain.output;
    const Outcome refused =
        occsim("bench " + small + " --plugin " + plugin +
               " --algos test-frustum --sweep threshold_pixels=4 --frames 3 --out " +
               (dir / "b").string());
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_EQ(lineCount(refused.output), 1u) << refused.output;
    EXPECT_NE(refused.output.find("culler 'test-frustum' needs conditional rendering, which this "
                                  "device does not offer"),
              std::string::npos)
        << refused.output;
    EXPECT_FALSE(fs::exists(dir / "b"));
    fs::remove_all(dir);
}

TEST(PluginCli, APluginsOptionsAreCheckedLikeABuiltinsAtTheirJsonPointer) {
    const fs::path dir = tempDir("cli-options");
    const struct {
        nlohmann::json culling;
        std::string expected;
    } cases[] = {
        {{{"test-frustum", {{"budget", 0}}}},
         "/culling/test-frustum/budget: expected an integer in [1, 1000] (objects), got 0"},
        {{{"test-frustum", {{"budget", 2.5}}}},
         "/culling/test-frustum/budget: expected an integer in [1, 1000] (objects), got 2.5"},
        {{{"test-frustum", {{"budget", "ten"}}}},
         "/culling/test-frustum/budget: expected an integer in [1, 1000] (objects)"},
        {{{"test-frustum", {{"bugdet", 3}}}},
         "/culling/test-frustum/bugdet: unknown key 'bugdet'; did you mean 'budget'?"},
        {{{"algorithm", "test-frustrum"}}, "/culling/algorithm"},
    };
    for (const auto& c : cases) {
        const fs::path scenario = scenarioWithPlugin(dir, c.culling);
        const Outcome o = occsim("bench " + scenario.string() + " --out " + (dir / "out").string());
        EXPECT_EQ(o.exit_code, 2) << o.output;
        EXPECT_EQ(lineCount(o.output), 1u) << o.output;
        EXPECT_NE(o.output.find(scenario.string() + ": " + c.expected), std::string::npos)
            << o.output;
        EXPECT_FALSE(fs::exists(dir / "out"));
    }
    fs::remove_all(dir);
}

TEST(PluginCli, APluginsCullerRunsBesideTheBuiltinsInBenchRegressAndJunit) {
    const fs::path dir = tempDir("cli-run");
    // bench without --algos runs the plugin's culler beside every built-in, error measured.
    const fs::path scenario = scenarioWithPlugin(dir, {{"test-frustum", {{"budget", 20}}}});
    const Outcome bench =
        occsim("bench " + scenario.string() + " --error --deterministic-latency 4 --out " +
               (dir / "bench").string());
    ASSERT_EQ(bench.exit_code, 0) << bench.output;
    EXPECT_NE(bench.output.find("\ntest-frustum "), std::string::npos) << bench.output;
    const nlohmann::json summary = nlohmann::json::parse(text(dir / "bench/summary.json"));
    bool found = false;
    for (const nlohmann::json& a : summary["algorithms"]) {
        if (a["algorithm"] != "test-frustum") continue;
        found = true;
        EXPECT_EQ(a["error"]["pixels_total"], 0) << "frustum culling hides nothing";
    }
    EXPECT_TRUE(found) << summary.dump();
    EXPECT_NE(text(dir / "bench/report.md").find("test-frustum"), std::string::npos);

    // A regression baseline and a JUnit file with the plugin's culler in them.
    const fs::path expecting =
        scenarioWithPlugin(dir, {{"algorithm", "test-frustum"}},
                           {{"algorithms", {"vfc", "test-frustum"}}, {"deterministic_latency", 4}});
    const Outcome update =
        occsim("regress " + expecting.string() + " --update --out " + (dir / "regress").string());
    ASSERT_EQ(update.exit_code, 0) << update.output;
    const fs::path baseline = dir / "with-plugin.baseline.json";
    ASSERT_TRUE(fs::exists(baseline)) << update.output;
    EXPECT_NE(text(baseline).find("\"test-frustum\""), std::string::npos);
    const Outcome check =
        occsim("regress " + expecting.string() + " --junit " + (dir / "junit.xml").string() +
               " --out " + (dir / "regress").string());
    ASSERT_EQ(check.exit_code, 0) << check.output;
    EXPECT_NE(text(dir / "junit.xml").find("test-frustum"), std::string::npos);
    fs::remove_all(dir);
}

TEST(PluginCli, OccsimCullersListsAPluginsCullerAndItsOptions) {
    const Outcome o = occsim("cullers --plugin " + pluginFile("good").string());
    ASSERT_EQ(o.exit_code, 0) << o.output;
    EXPECT_NE(o.output.find(
                  "test-frustum: frustum culling, from a plugin (tests) (conservative, plugin "),
              std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("  margin = 1  number [0, 5] m (tunable 0 to 2)"), std::string::npos)
        << o.output;
}

}  // namespace
