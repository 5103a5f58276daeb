// The docs keep their promises: every command block marked runnable (tests/support/doc_blocks.h)
// runs as written, under the shell it names, and exits as documented; the recipes of
// docs/regression.md (shards merged, a Slurm job array, a Kubernetes Indexed Job) among them.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "doc_blocks.h"
#include "shell_command.h"

namespace occsim::testing {
namespace {

namespace fs = std::filesystem;

fs::path tempPath(const std::string& name) {
    const auto p =
        fs::temp_directory_path() / ("occsim-docs-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(p);
    return p;
}

std::string readFile(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs every block of `doc` in `dir` and expects each to exit as its marker says.
void runEveryBlock(const std::string& doc, const fs::path& dir) {
    const std::vector<DocBlock> blocks = runnableBlocks(readDoc(doc), doc);
    EXPECT_FALSE(blocks.empty()) << doc << " marks no block runnable";
    for (const DocBlock& block : blocks) {
        const Outcome o = runBlock(block, dir);
        EXPECT_EQ(o.exit_code, block.expect) << block.where << ":\n" << block.script << o.output;
    }
}

// The folder docs/regression.md's commands run in: scenarios/small holding copies of four small
// scenarios and their baselines (copies: a block runs --update; four: each shard of four gets
// one, and regress runs them in seconds), scenarios/assets the glTF files they read.
fs::path regressionFolder(const std::string& name) {
    const fs::path dir = tempPath(name);
    const fs::path source = fs::path(OCCSIM_SOURCE_DIR) / "scenarios";
    fs::create_directories(dir / "scenarios" / "small");
    for (const char* scenario :
         {"city-small", "shared-faces-small", "plant-small", "library-small"}) {
        for (const std::string suffix : {".json", ".baseline.json"}) {
            fs::copy_file(source / "small" / (scenario + suffix),
                          dir / "scenarios" / "small" / (scenario + suffix));
        }
    }
    fs::create_directory_symlink(source / "assets", dir / "scenarios" / "assets");
    return dir;
}

TEST(Docs, EveryRunnableCommandBlockExitsAsDocumented) {
    const auto dir = tempPath("blocks");
    fs::create_directories(dir);
    fs::create_directory_symlink(fs::path(OCCSIM_SOURCE_DIR) / "scenarios", dir / "scenarios");

    // The runner can fail: a marked command that fails is caught.
    const auto broken =
        runnableBlocks("<!-- runnable -->\n```sh\noccsim frobnicate\n```\n", "self-test.md");
    ASSERT_EQ(broken.size(), 1u);
    EXPECT_NE(runBlock(broken[0], dir).exit_code, 0);

    // Twice: a rerun into the folders the first run left (a run replaces its --out as a whole)
    // must work just the same.
    for (int pass = 0; pass < 2; ++pass) {
        for (const char* doc : {"README.md", "docs/cli.md"}) runEveryBlock(doc, dir);
    }
    fs::remove_all(dir);
}

// A marker's options are read, and one the runner does not know is an error, not ignored.
TEST(Docs, RunnableMarkersNameTheShellTheExitStatusAndTheFileAndUnknownOptionsFail) {
    const auto blocks = runnableBlocks(
        "<!-- runnable: exit 1, shell bash, id x -->\n```sh\nfalse\n```\n"
        "<!-- runnable: file job.sh -->\n```sh\n#!/bin/bash\n```\n"
        "<!-- runnable: completions 4, volume /results -->\n```yaml\ncommand: [\"sh\"]\n```\n",
        "self-test.md");
    ASSERT_EQ(blocks.size(), 3u);
    EXPECT_EQ(blocks[0].expect, 1);
    EXPECT_EQ(blocks[0].shell, "bash");
    EXPECT_EQ(blocks[0].id, "x");
    EXPECT_EQ(blocks[1].file, "job.sh");
    EXPECT_EQ(blocks[2].completions, 4);
    EXPECT_EQ(blocks[2].volume, "/results");
    EXPECT_NONFATAL_FAILURE(
        runnableBlocks("<!-- runnable: exit 1, retries 3 -->\n```sh\ntrue\n```\n", "self-test.md"),
        "unknown runnable option ' retries 3'");
}

// What Slurm does to --wrap: the command runs under /bin/sh, dash on Debian, where a bash-only
// command (braces expanded) does not do what it says. The stand-in runs it under dash too.
TEST(Docs, TheSbatchStandInRunsWrapUnderDashAsSlurmDoes) {
    const auto dir = tempPath("dash");
    fs::create_directories(dir / "shard-0");
    fs::create_directories(dir / "shard-1");
    const Outcome braces = runScript(
        "bash", "sbatch --parsable --wrap 'for d in shard-{0..1}; do test -d $d; done'\n", dir);
    EXPECT_NE(braces.exit_code, 0) << braces.output;
    EXPECT_NE(braces.output.find("exited 1"), std::string::npos) << braces.output;
    const Outcome spelt = runScript(
        "bash", "sbatch --parsable --wrap 'for d in shard-0 shard-1; do test -d $d; done'\n", dir);
    EXPECT_EQ(spelt.exit_code, 0) << spelt.output;
    fs::remove_all(dir);
}

// docs/regression.md's commands, in the doc's order: regress, shards merged, the Slurm job array
// and its merge (--wrap under dash), the Kubernetes Indexed Job and its merge, the history.
TEST(Docs, EveryRegressionRecipeRunsAsWrittenUnderTheShellItNames) {
    const fs::path dir = regressionFolder("recipes");
    runEveryBlock("docs/regression.md", dir);
    for (const char* merged : {"results/merged", "volume/results/merged"}) {
        EXPECT_TRUE(fs::exists(dir / merged / "checks.tsv")) << merged << " was not merged";
    }
    fs::remove_all(dir);
}

// The Kubernetes recipe when a check fails: every pod still exits 0 (or the Indexed Job would
// retry it, end Failed, and the merge would never run), and the merge reports the failure with
// exit status 1. A pod given bad input still fails.
TEST(Docs, TheKubernetesRecipeMergesAShardWhoseCheckFailed) {
    const fs::path dir = regressionFolder("k8s");
    fs::remove(dir / "scenarios" / "small" / "plant-small.baseline.json");  // its check fails
    DocBlock pods = docBlockWithId("docs/regression.md", "k8s-pods");
    DocBlock merge = docBlockWithId("docs/regression.md", "k8s-merge");
    ASSERT_EQ(pods.completions, 4);
    const Outcome ran = runBlock(pods, dir);
    EXPECT_EQ(ran.exit_code, 0) << ran.output;
    merge.expect = 1;
    const Outcome merged = runBlock(merge, dir);
    EXPECT_EQ(merged.exit_code, 1) << merged.output;
    const std::string report = readFile(dir / "volume" / "results" / "merged" / "report.md");
    EXPECT_NE(report.find("plant-small"), std::string::npos) << report;
    EXPECT_NE(report.find("no baseline file"), std::string::npos) << report;
    EXPECT_NE(report.find("**Some checks failed.**"), std::string::npos) << report;

    replaceAll(pods.script, "regress ", "regress --shard 9/4 ");
    EXPECT_EQ(runBlock(pods, dir).exit_code, 2) << "bad input must fail the pod";
    fs::remove_all(dir);
}

// The benchmark scripts keep core dumps on (docs/stability.md): the next crash in a long run
// leaves a core, and the script says where it goes.
TEST(Scripts, BenchmarkScriptsTurnCoreDumpsOnAndSayWhereTheCoreGoes) {
    const fs::path scripts = fs::path(OCCSIM_SOURCE_DIR) / "scripts";
    for (const char* script : {"bench.sh", "results.sh", "ablation.sh", "valgrind.sh"}) {
        const std::string text = readFile(scripts / script);
        const size_t sourced = text.find("\nsource scripts/core_dumps.sh");
        const size_t runs = text.find("/sim/occsim");
        EXPECT_NE(sourced, std::string::npos) << script;
        EXPECT_LT(sourced, runs) << script << ": core dumps on before occsim runs";
    }
    const Outcome o = shell("bash -c 'ulimit -S -c 0; cd " + singleQuoted(OCCSIM_SOURCE_DIR) +
                            "; source scripts/core_dumps.sh; echo \"soft $(ulimit -S -c) hard "
                            "$(ulimit -H -c)\"'");
    EXPECT_EQ(o.exit_code, 0) << o.output;
    if (shell("bash -c 'ulimit -H -c'").output != "0\n") {
        EXPECT_NE(o.output.find("core dumps: on"), std::string::npos) << o.output;
        EXPECT_NE(o.output.find("a crash leaves its core at "), std::string::npos) << o.output;
        const size_t at = o.output.find("soft ");
        ASSERT_NE(at, std::string::npos) << o.output;
        std::string soft, word, hard;
        std::istringstream(o.output.substr(at)) >> word >> soft >> word >> hard;
        EXPECT_EQ(soft, hard) << "the limit raised to the hard limit";
    }
}

}  // namespace
}  // namespace occsim::testing
