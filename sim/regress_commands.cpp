#include "sim/regress_commands.h"

#include <cstdio>

#include "sim/output/atomic_file.h"
#include "sim/regress/history.h"
#include "sim/regress/history_report.h"
#include "sim/regress/merge.h"
#include "sim/regress/result_files.h"
#include "sim/regress/shard_result.h"

namespace occsim_cli {
namespace {

using occsim::ResultFileError;

void appendAndSay(const std::string& history_dir,
                  const std::vector<std::pair<std::string, occsim::Json>>& summaries,
                  const std::string& commit) {
    const occsim::HistoryEntry entry = occsim::historyEntryNow(summaries, commit);
    const auto file = occsim::appendHistory(history_dir, entry);
    std::printf(
        "history: %s (commit %s, %zu scenarios)%s\n", file.string().c_str(), entry.commit.c_str(),
        entry.scenarios.size(),
        entry.commit == "unknown" ? "; no commit found: pass --commit or set OCCSIM_COMMIT" : "");
}

bool sameFolder(const std::filesystem::path& a, const std::filesystem::path& b) {
    std::error_code ec;
    return std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec) &&
           std::filesystem::equivalent(a, b, ec);
}

}  // namespace

void checkHistoryFlag(const std::string& history_dir) {
    if (!history_dir.empty()) occsim::checkHistoryFolder(history_dir);
}

void writeRegressResults(const occsim::RegressOptions& options, const occsim::RegressReport& report,
                         const std::string& history_dir, const std::string& commit) {
    occsim::ShardResult result;
    result.set = occsim::scenarioSetOf(options.inputs);
    result.shard = options.shard;
    result.report = report;
    occsim::writeShardResult(options.out_dir, result);
    if (history_dir.empty()) return;
    std::vector<std::pair<std::string, occsim::Json>> summaries;
    for (const occsim::ScenarioOutcome& s : report.scenarios) {
        occsim::Json summary = occsim::scenarioSummary(options.out_dir, s);
        if (!summary.is_null()) summaries.emplace_back(s.name, std::move(summary));
    }
    appendAndSay(history_dir, summaries, commit);
}

int mergeCommand(const MergeFlags& flags) {
    if (flags.out.empty())
        throw ResultFileError("--out: empty; expected a folder (created when missing)");
    for (const std::string& dir : flags.dirs) {
        if (sameFolder(dir, flags.out)) {
            throw ResultFileError("--out " + flags.out + ": is the shard folder " + dir +
                                  "; expected a folder of its own for the merged report");
        }
    }
    if (!flags.history.empty()) occsim::checkHistoryFolder(flags.history);
    const occsim::MergedRun run = occsim::mergeShards({flags.dirs.begin(), flags.dirs.end()});
    occsim::writeMergedReport(flags.out, run);
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
                summaries.emplace_back(run.report.scenarios[k].name, run.summaries[k]);
        }
        appendAndSay(flags.history, summaries, flags.commit);
    }
    return run.report.passed() ? 0 : 1;
}

int historyCommand(const HistoryFlags& flags) {
    if (flags.out.empty())
        throw ResultFileError("--out: empty; expected a folder (created when missing)");
    if (sameFolder(flags.dir, flags.out)) {
        throw ResultFileError("--out " + flags.out +
                              ": is the history folder; expected a folder of its own");
    }
    std::vector<occsim::HistoryEntry> runs = occsim::readHistory(flags.dir);
    if (runs.empty())
        throw ResultFileError(flags.dir +
                              ": no history entries (*.json); expected at least one run");
    occsim::HistoryOptions options;
    options.window = flags.window;
    options.min_change = flags.min_change;
    const occsim::HistoryAnalysis analysis = occsim::analyseHistory(std::move(runs), options);
    const auto files = occsim::writeHistoryReport(flags.out, analysis, options);
    for (const auto& c : analysis.flagged) std::printf("changed: %s\n", c.text().c_str());
    for (const auto& s : analysis.not_compared) std::printf("not compared: %s\n", s.c_str());
    std::printf(
        "history: %zu runs, %zu series, %zu scenarios, %zu changes flagged; written %s/report.md "
        "and %zu "
        "plots\n",
        analysis.runs.size(), analysis.series.size(), analysis.scenarios.size(),
        analysis.flagged.size(), flags.out.c_str(), files.size() - 1);
    return flags.fail_on_change && !analysis.flagged.empty() ? 1 : 0;
}

}  // namespace occsim_cli
