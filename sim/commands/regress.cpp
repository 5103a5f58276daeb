#include "sim/commands/regress.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "occsim/culling/contract/input_error.h"
#include "sim/commands/exit_codes.h"
#include "sim/commands/flag_checks.h"
#include "sim/commands/regress_results.h"
#include "sim/output/atomic_file.h"
#include "sim/output/run_folder.h"
#include "sim/regress/regress.h"
#include "sim/scenario/culling_file.h"

namespace occsim_cli {

CLI::App* addRegress(CLI::App& app, RegressFlags& flags) {
    CLI::App* regress = app.add_subcommand(
        "regress",
        "Run every scenario with an expect block (files or folders, recursively) and check it");
    regress->add_option("paths", flags.inputs, "Scenario files or folders")->required();
    regress->add_flag("--update", flags.update,
                      "Rewrite the baselines from this run (prints what changed)");
    regress->add_flag(
        "--allow-empty", flags.allow_empty,
        "Exit 0 even when no scenario found has an expect block (default: that fails)");
    regress->add_flag("--exit-zero-on-failed-checks", flags.exit_zero_on_failed_checks,
                      "Exit 0 when checks fail (they stay in the results, for merge to report); "
                      "bad input (2) and failures while running (1) still fail");
    regress->add_option("--junit", flags.junit, "Write JUnit XML results to this file");
    regress->add_option("--shard", flags.shard,
                        "Run shard i of n (i/n); default from Slurm or Kubernetes job variables");
    regress->add_option("--out", flags.out,
                        "Output folder for data and failure pictures (each scenario's folder "
                        "in it replaced as a whole)");
    regress->add_flag("--wait-lock", flags.wait_lock,
                      "Wait for another regress writing the same --out to finish (default: exit)");
    regress->add_option(
        "--culling", flags.culling_file,
        "Culling options from this file, overriding every scenario's (see run --help)");
    addPluginFlag(regress, flags.plugins);
    addBackendFlags(regress, flags.backend);
    regress->add_flag("--quiet", flags.quiet,
                      "No progress on stderr (default: [i/n] and a bar on a terminal, else a "
                      "line every 10 s)");
    regress->add_option("--record", flags.record, kRecordHelp)->delimiter(',');
    regress->add_option(
        "--history", flags.history,
        "Append this run's figures to a history folder (occsim history DIR reports it)");
    regress->add_option("--commit", flags.commit,
                        "Commit recorded in the history (default: $OCCSIM_COMMIT, $GITHUB_SHA, "
                        "$CI_COMMIT_SHA or git rev-parse HEAD)");
    return regress;
}

int regressCommand(const RegressFlags& flags) {
    checkOutputFile("--junit", flags.junit, flags.junit_given);
    checkWritableFile("--junit", flags.junit);
    checkOutputFolder("--out", flags.out, true);
    for (const std::string& input : flags.inputs) {
        // The next run would take this run's summaries for scenarios, or replace its inputs.
        if (std::filesystem::is_directory(input) && sameOrInside(input, flags.out)) {
            throw occsim::InputError("--out " + flags.out + ": holds the scenario folder " + input +
                                     "; expected an output folder apart from the scenarios");
        }
    }
    occsim_cli::checkHistoryFlag(flags.history);
    const bool record_objects = recordsObjects(flags.record);
    checkWritableFolder("--history", flags.history);
    // Each scenario's folder under --out is one unit with its own lock (runRegression); this
    // lock keeps two regress runs out of the folder's shard.json and junit.xml.
    const occsim::FolderLock lock(flags.out, flags.wait_lock);
    occsim::checkRegressFolder(flags.out);
    loadPlugins(flags.plugins);
    occsim::RegressOptions options;
    options.backend = backendChoice(flags.backend);
    for (const std::string& plugin : flags.plugins)
        options.rerun_flags.insert(options.rerun_flags.end(), {"--plugin", plugin});
    if (!flags.culling_file.empty())
        options.rerun_flags.insert(options.rerun_flags.end(), {"--culling", flags.culling_file});
    if (flags.backend.backend != "auto")
        options.rerun_flags.insert(options.rerun_flags.end(), {"--backend", flags.backend.backend});
    if (record_objects)
        options.rerun_flags.insert(options.rerun_flags.end(), {"--record", "objects"});
    if (flags.backend.device >= 0) {
        options.rerun_flags.insert(options.rerun_flags.end(),
                                   {"--device", std::to_string(flags.backend.device)});
    }
    if (!flags.culling_file.empty()) {
        options.adjust_scenario =
            [culling = occsim::readCullingFile(flags.culling_file)](occsim::Scenario& s) {
                occsim::applyCullingFile(culling, s);
            };
    }
    for (const auto& input : flags.inputs) options.inputs.emplace_back(input);
    try {
        options.shard = flags.shard.empty() ? occsim::shardFromEnvironment(std::getenv)
                                            : occsim::parseShard(flags.shard);
    } catch (const std::invalid_argument& e) {
        throw occsim::InputError(std::string("--shard: ") + e.what());
    }
    options.update = flags.update;
    options.record_objects = record_objects;
    options.out_dir = flags.out;
    options.wait_lock = flags.wait_lock;
    options.progress = occsim::stderrProgressStyle(flags.quiet);
    watchFrames();
    const occsim::RegressReport report = occsim::runRegression(options);
    std::printf("%s", report.table().c_str());
    size_t failed = 0, skipped = 0;
    for (const auto& s : report.scenarios) {
        failed += !s.passed();
        skipped += s.skipped;
        if (!s.note.empty() && !s.skipped) std::printf("%s\n", s.note.c_str());
        for (const auto& capture : s.captures)
            std::printf("picture of the worst frame: %s\n", capture.c_str());
    }
    if (!flags.junit.empty()) {
        const std::filesystem::path junit_path(flags.junit);
        if (junit_path.has_parent_path())
            std::filesystem::create_directories(junit_path.parent_path());
        occsim::writeFileAtomically(junit_path, occsim::junitXml(report));
    }
    // A stopped run's figures are no flags.history: only its flags.shard result is written (which
    // merge refuses, a scenario of the set being missing).
    if (!flags.update) {
        occsim_cli::writeRegressResults(options, report, report.stop_signal ? "" : flags.history,
                                        flags.commit);
    }
    std::printf("regress: %zu scenarios (shard %u/%u), %zu failed, %zu skipped\n",
                report.scenarios.size(), options.shard.index, options.shard.count, failed, skipped);
    if (report.stop_signal) {
        std::fflush(stdout);
        std::fprintf(stderr,
                     "occsim regress: %s; written to %s%s; run the same command again for a "
                     "whole run\n",
                     report.stopped.c_str(), flags.out.c_str(),
                     flags.history.empty() ? "" : ", nothing appended to the history");
        return 128 + report.stop_signal;
    }
    // Green with nothing checked would let a CI job pass on a wrong path or a lost expect block.
    if (report.scenarios.size() == skipped && !flags.allow_empty) {
        std::fprintf(
            stderr,
            "occsim regress: nothing was checked: %s (--allow-empty when that is expected)\n",
            report.scenarios.empty() ? "no scenario file found under the paths given"
                                     : "no scenario found has an expect block");
        return kExitFailure;
    }
    // A flags.shard under a scheduler that retries failed tasks (a Kubernetes Indexed Job) must
    // finish so that the merge runs; the failed checks are in its results and the merge exits 1.
    if (!report.passed() && flags.exit_zero_on_failed_checks) {
        std::printf(
            "regress: failed checks exit 0 (--exit-zero-on-failed-checks): merge reports them\n");
        return 0;
    }
    return report.passed() ? 0 : kExitFailure;
}

}  // namespace occsim_cli
