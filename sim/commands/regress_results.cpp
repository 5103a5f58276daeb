#include "sim/commands/regress_results.h"

#include <cstdio>

#include "sim/regress/history.h"

namespace occsim_cli {

void appendHistoryAndSay(const std::string& history_dir,
                         const std::vector<std::pair<std::string, occsim::Json>>& summaries,
                         const std::string& commit, const std::vector<std::string>& hosts,
                         const std::string& cpu) {
    occsim::HistoryEntry entry = occsim::historyEntryNow(summaries, commit);
    // A merged run's figures come from the machines its shards ran on, not from the one merging.
    if (!hosts.empty()) {
        entry.hostname.clear();
        for (const std::string& h : hosts)
            entry.hostname += (entry.hostname.empty() ? "" : ",") + h;
        entry.cpu = cpu;
    }
    const auto file = occsim::appendHistory(history_dir, entry);
    std::printf(
        "history: %s (commit %s, %zu scenarios)%s\n", file.string().c_str(), entry.commit.c_str(),
        entry.scenarios.size(),
        entry.commit == "unknown" ? "; no commit found: pass --commit or set OCCSIM_COMMIT" : "");
}

void checkHistoryFlag(const std::string& history_dir) {
    if (!history_dir.empty()) occsim::checkHistoryFolder(history_dir);
}

void writeRegressResults(const occsim::RegressOptions& options, const occsim::RegressReport& report,
                         const std::string& history_dir, const std::string& commit) {
    occsim::ShardResult result;
    result.set = occsim::scenarioSetOf(options.inputs);
    result.shard = options.shard;
    result.hostname = occsim::thisHostName();
    result.cpu = occsim::thisCpuModel();
    result.report = report;
    occsim::writeShardResult(options.out_dir, result);
    if (history_dir.empty()) return;
    std::vector<std::pair<std::string, occsim::Json>> summaries;
    for (const occsim::ScenarioOutcome& s : report.scenarios) {
        occsim::Json summary = occsim::scenarioSummary(options.out_dir, s);
        if (!summary.is_null()) summaries.emplace_back(s.id, std::move(summary));
    }
    appendHistoryAndSay(history_dir, summaries, commit);
}

}  // namespace occsim_cli
