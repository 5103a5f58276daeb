// `occsim merge`: the shards of one sharded regression run (each shard's --out folder, as
// written by writeShardResult) joined into one report, in the order a one-machine run of the
// same set reports them. Everything is checked before anything is written: every shard i/n of
// one n present once, all cut from the same scenario set, every scenario of the set run by
// exactly one shard, every junit.xml whole.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sim/regress/shard_result.h"
#include "sim/scenario/json_reader.h"

namespace occsim {

struct MergedRun {
    ScenarioSet set;
    std::vector<std::filesystem::path> shard_dirs;  // by shard index
    RegressReport report;                           // in the set's order
    std::vector<uint32_t> shard_of;                 // per scenario of report: which shard ran it
    std::vector<Json> summaries;                    // per scenario: its summary.json, or null
    // Where the shards ran: one kind of CPU (checked), the hosts sorted.
    std::string cpu;
    std::vector<std::string> hosts;
};

// Throws ResultFileError (one line, naming the folder or file) on any inconsistency: shards of
// different sets or counts, a scenario in no shard or in two, a summary that belongs to another
// scenario, shards rendered on different backends, renderers or CPUs.
MergedRun mergeShards(const std::vector<std::filesystem::path>& dirs);

// The merged report's text: the table of every check (exactly what `occsim regress` prints for
// the same set on one machine), the notes, and which shard ran what.
std::string mergedMarkdown(const MergedRun& run);
Json mergedSummaryJson(const MergedRun& run);

// One line per check (scenario, check, expected, got, result; tab-separated, with a header):
// the table without its padding, for comparing two reports line by line.
std::string checksTsv(const RegressReport& report);

// out/junit.xml, out/report.md, out/checks.tsv, out/summary.json, each atomically.
void writeMergedReport(const std::filesystem::path& out, const MergedRun& run);

}  // namespace occsim
