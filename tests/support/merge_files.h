// What the tests of merging and of the history share, without a process: fresh folders, whole
// files read and written, history entries, and the shards of a made-up regression run of six
// scenarios as `occsim regress --shard` leaves them. occsim run as a command:
// tests/system/merge_commands.h.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim/regress/history.h"
#include "sim/regress/history_report.h"
#include "sim/regress/merge.h"
#include "sim/regress/result_files.h"
#include "sim/regress/shard_result.h"

namespace occsim::merge_files {

namespace fs = std::filesystem;

inline fs::path freshDir(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("occsim-merge-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

inline std::string readFile(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void writeFile(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

// A history entry of machine `host`, with statistical's speedup and queries in scenario s.
inline HistoryEntry entry(const std::string& date, const std::string& host, double speedup,
                          double queries = 40) {
    HistoryEntry e;
    e.commit = "c0ffee" + date.substr(8, 2);
    e.date = date;
    e.hostname = host;
    e.cpu = "Test CPU";
    e.renderer = "llvmpipe";
    e.backend = "egl";
    e.scenarios["s"]["vfc"] = {1.0, 0, 120, 0};
    e.scenarios["s"]["statistical"] = {speedup, queries, 60, 0};
    e.scenarios["t"]["statistical"] = {2.0, 10, 20, 0};
    return e;
}

inline fs::path historyOf(const std::string& name, const std::vector<HistoryEntry>& entries) {
    const fs::path dir = freshDir(name);
    for (const HistoryEntry& e : entries) appendHistory(dir / "history", e);
    return dir / "history";
}

inline HistoryOptions windowOf(size_t n) {
    HistoryOptions o;
    o.window = n;
    return o;
}

// Six scenarios a..f; scenario c fails one check, e is skipped.
inline ScenarioSet sixScenarios() {
    ScenarioSet set;
    set.id = "0123456789abcdef";
    for (const char* n : {"a", "b", "c", "d", "e", "f"}) {
        set.scenarios.push_back(std::string("scenarios/") + n + ".json");
        set.ids.push_back(n);
    }
    return set;
}

// The outcome of one of the six: two checks (c fails the second), e skipped.
inline ScenarioOutcome outcomeOf(const std::string& file) {
    ScenarioOutcome o;
    o.scenario = file;
    o.id = o.name = fs::path(file).stem().string();
    if (o.name == "e") {
        o.skipped = true;
        o.note = "no expect block";
        return o;
    }
    o.checks.push_back({"zero error pixels: chc", "0 on every frame", "0 (3 tie px)", true});
    o.checks.push_back({"queries per frame = baseline: chc", "identical over 3 frames",
                        o.name == "c" ? "frame 1: 7 <b>&\"" : "identical over 3 frames",
                        o.name != "c"});
    o.seconds = 0.25;
    return o;
}

// A scenario's summary.json as runRegression writes it: its scenario block names it.
inline std::string summaryOf(const ScenarioOutcome& o) {
    return Json{{"scenario", {{"id", o.id}, {"name", o.name}, {"file", o.scenario}}}}.dump() + "\n";
}

// Shard i of n of the six, as `occsim regress --shard i/n --out dir` leaves it.
inline fs::path writeShard(const fs::path& root, uint32_t i, uint32_t n,
                           const ScenarioSet& set = sixScenarios()) {
    ShardResult r;
    r.set = set;
    r.shard = {i, n};
    for (size_t k = i; k < set.scenarios.size(); k += n)
        r.report.scenarios.push_back(outcomeOf(set.scenarios[k]));
    const fs::path dir = root / ("shard-" + std::to_string(i));
    writeShardResult(dir, r);
    // Every scenario that ran leaves its summary.json (runRegression's writeRunOutputs).
    for (const ScenarioOutcome& o : r.report.scenarios) {
        if (!o.ran()) continue;
        fs::create_directories(dir / o.id);
        writeFile(dir / o.id / "summary.json", summaryOf(o));
    }
    return dir;
}

// The six scenarios' outcomes as one machine would report them.
inline RegressReport wholeReport() {
    RegressReport report;
    for (const auto& f : sixScenarios().scenarios) report.scenarios.push_back(outcomeOf(f));
    return report;
}

// What merging `dirs` refuses with, or "" when it merges them.
inline std::string mergeError(const std::vector<fs::path>& dirs) {
    try {
        mergeShards(dirs);
    } catch (const ResultFileError& e) {
        return e.what();
    }
    return "";
}

}  // namespace occsim::merge_files
