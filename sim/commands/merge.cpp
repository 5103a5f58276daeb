#include "sim/commands/merge.h"

#include <cstdio>
#include <filesystem>

#include "occsim/culling/contract/input_error.h"
#include "sim/commands/flag_checks.h"
#include "sim/commands/regress_results.h"
#include "sim/output/atomic_file.h"
#include "sim/output/run_folder.h"
#include "sim/regress/history.h"
#include "sim/regress/merge.h"
#include "sim/regress/result_files.h"

namespace occsim_cli {

using occsim::ResultFileError;

CLI::App* addMerge(CLI::App& app, MergeFlags& flags) {
    CLI::App* merge = app.add_subcommand(
        "merge",
        "Join the --out folders of the shards of one regress run into one report, checking that "
        "every scenario ran exactly once");
    merge->add_option("shards", flags.dirs, "The shards' --out folders")->required();
    merge->add_option("--out", flags.out, "Folder for the merged report (default out/merged)");
    merge->add_option("--junit", flags.junit, "Also write the merged JUnit XML to this file");
    merge->add_option("--history", flags.history,
                      "Append the merged run's figures to a history folder");
    merge->add_option("--commit", flags.commit, "Commit recorded in the history (as for regress)");
    return merge;
}

int mergeCommand(const MergeFlags& flags) {
    if (flags.out.empty())
        throw occsim::InputError("--out: empty; expected a folder (created when missing)");
    for (const std::string& dir : flags.dirs) {
        if (sameFolder(dir, flags.out)) {
            throw occsim::InputError("--out " + flags.out + ": is the shard folder " + dir +
                                     "; expected a folder of its own for the merged report");
        }
    }
    checkWritableFile("--junit", flags.junit);
    if (!flags.history.empty()) occsim::checkHistoryFolder(flags.history);
    checkWritableFolder("--history", flags.history);
    // The merged report's folder follows the run folder's rule (run_folder.h): replaced as a
    // whole, and only when it is empty, absent or an earlier occsim output.
    const occsim::FolderLock lock(flags.out, false);
    occsim::checkRunFolder(occsim::resolvedFolder(flags.out));
    const occsim::MergedRun run = occsim::mergeShards({flags.dirs.begin(), flags.dirs.end()});
    occsim::StagedRunFolder folder(flags.out);
    occsim::writeMergedReport(folder.staging(), run);
    folder.publish();
    if (!flags.junit.empty()) {
        const std::filesystem::path junit(flags.junit);
        if (junit.has_parent_path()) std::filesystem::create_directories(junit.parent_path());
        occsim::writeFileAtomically(junit, occsim::junitXml(run.report));
    }
    std::printf("%s", run.report.table().c_str());
    size_t failed = 0, skipped = 0;
    for (const auto& s : run.report.scenarios) {
        failed += !s.passed();
        skipped += s.skipped;
    }
    std::printf(
        "merge: %zu scenarios from %zu shards, %zu failed, %zu skipped; written "
        "%s/{junit.xml,report.md,"
        "checks.tsv,summary.json}\n",
        run.report.scenarios.size(), run.shard_dirs.size(), failed, skipped, flags.out.c_str());
    if (!flags.history.empty()) {
        std::vector<std::pair<std::string, occsim::Json>> summaries;
        for (size_t k = 0; k < run.report.scenarios.size(); ++k) {
            if (!run.summaries[k].is_null())
                summaries.emplace_back(run.report.scenarios[k].id, run.summaries[k]);
        }
        appendHistoryAndSay(flags.history, summaries, flags.commit, run.hosts, run.cpu);
    }
    return run.report.passed() ? 0 : 1;
}

}  // namespace occsim_cli
