#include "sim/regress/merge.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "sim/output/atomic_file.h"
#include "sim/regress/result_files.h"

namespace occsim {
namespace {

std::string joinIndices(const std::vector<uint32_t>& v) {
    std::string s;
    for (uint32_t i : v) s += (s.empty() ? "" : ", ") + std::to_string(i);
    return s.empty() ? "none" : s;
}

// Every shard cut from the first one's set, with the first one's n, each index once.
void checkShardsAgree(const std::vector<ShardResult>& shards) {
    const ShardResult& first = shards.front();
    std::map<uint32_t, const ShardResult*> by_index;
    for (const ShardResult& s : shards) {
        const std::string where = (s.dir / "shard.json").string();
        if (s.set.id != first.set.id || s.set.scenarios != first.set.scenarios ||
            s.set.ids != first.set.ids) {
            throw ResultFileError(where + ": /scenario_set: from another scenario set (id " +
                                  s.set.id + ", " + std::to_string(s.set.scenarios.size()) +
                                  " scenarios) than " + (first.dir / "shard.json").string() +
                                  " (id " + first.set.id + ", " +
                                  std::to_string(first.set.scenarios.size()) +
                                  " scenarios); expected every shard from the same scenario files");
        }
        if (s.shard.count != first.shard.count) {
            throw ResultFileError(where + ": /shard: shard " + std::to_string(s.shard.index) + "/" +
                                  std::to_string(s.shard.count) + ", but " +
                                  (first.dir / "shard.json").string() + " is of " +
                                  std::to_string(first.shard.count) + " shards");
        }
        const auto [it, inserted] = by_index.emplace(s.shard.index, &s);
        if (!inserted) {
            throw ResultFileError(where + ": /shard: shard " + std::to_string(s.shard.index) + "/" +
                                  std::to_string(s.shard.count) + " ran twice (also in " +
                                  (it->second->dir / "shard.json").string() +
                                  "); expected each shard once");
        }
    }
    if (by_index.size() != first.shard.count) {
        std::vector<uint32_t> have, missing;
        for (uint32_t i = 0; i < first.shard.count; ++i)
            (by_index.count(i) ? have : missing).push_back(i);
        throw ResultFileError("merge: shard(s) " + joinIndices(missing) + " of " +
                              std::to_string(first.shard.count) + " missing (given " +
                              joinIndices(have) + "); expected one folder per shard");
    }
}

// A history series is one kind of machine and backend (history.h): shards rendered on different
// backends or renderers, or on different CPUs, are not one run.
void checkOneMachineKind(MergedRun& run, const std::vector<ShardResult>& shards) {
    auto kindOf = [](const Json& summary) {
        if (!summary.is_object() || !summary.contains("machine")) return std::string();
        const Json& m = summary["machine"];
        return m.value("backend", std::string()) + ", " + m.value("gl_renderer", std::string());
    };
    std::string kind, where;
    for (size_t k = 0; k < run.summaries.size(); ++k) {
        const std::string here = kindOf(run.summaries[k]);
        if (here.empty()) continue;
        const std::string scenario = run.report.scenarios[k].scenario;
        if (kind.empty()) {
            kind = here;
            where = scenario;
        } else if (here != kind) {
            throw ResultFileError("merge: " + scenario + " was rendered on " + here + " but " +
                                  where + " on " + kind +
                                  "; expected every shard on one backend and renderer (merge each "
                                  "kind of machine apart)");
        }
    }
    for (const ShardResult& s : shards) {
        if (s.cpu != shards.front().cpu) {
            throw ResultFileError((s.dir / "shard.json").string() + ": /machine/cpu: " + s.cpu +
                                  ", but " + (shards.front().dir / "shard.json").string() +
                                  " ran on " + shards.front().cpu +
                                  "; expected every shard on one kind of machine");
        }
        if (std::find(run.hosts.begin(), run.hosts.end(), s.hostname) == run.hosts.end())
            run.hosts.push_back(s.hostname);
    }
    run.cpu = shards.front().cpu;
    std::sort(run.hosts.begin(), run.hosts.end());
}

}  // namespace

MergedRun mergeShards(const std::vector<std::filesystem::path>& dirs) {
    if (dirs.empty()) throw ResultFileError("merge: no shard folders given");
    std::vector<ShardResult> shards;
    for (const auto& dir : dirs) shards.push_back(readShardResult(dir));
    checkShardsAgree(shards);

    MergedRun run;
    run.set = shards.front().set;
    run.shard_dirs.resize(shards.front().shard.count);
    // Which shard ran each scenario; a scenario claimed twice or not in the set is refused.
    std::map<std::string, std::pair<const ShardResult*, const ScenarioOutcome*>> ran;
    for (const ShardResult& s : shards) {
        run.shard_dirs[s.shard.index] = s.dir;
        for (const ScenarioOutcome& o : s.report.scenarios) {
            const std::string where = (s.dir / "shard.json").string();
            if (std::find(run.set.scenarios.begin(), run.set.scenarios.end(), o.scenario) ==
                run.set.scenarios.end()) {
                throw ResultFileError(where + ": /scenarios: " + o.scenario +
                                      " is not in the shard's scenario set");
            }
            const auto [it, inserted] = ran.emplace(o.scenario, std::make_pair(&s, &o));
            if (!inserted) {
                throw ResultFileError(where + ": /scenarios: " + o.scenario +
                                      " is also claimed by " +
                                      (it->second.first->dir / "shard.json").string() +
                                      "; expected every scenario in exactly one shard");
            }
        }
    }
    for (size_t k = 0; k < run.set.scenarios.size(); ++k) {
        const std::string& file = run.set.scenarios[k];
        const auto it = ran.find(file);
        if (it == ran.end()) {
            throw ResultFileError("merge: " + file + " of scenario set " + run.set.id +
                                  " ran in no shard; expected every scenario in exactly one shard");
        }
        const auto& [shard, outcome] = it->second;
        if (outcome->id != run.set.ids[k]) {
            throw ResultFileError((shard->dir / "shard.json").string() + ": /scenarios: " + file +
                                  " filed as '" + outcome->id + "'; expected its id in the set, '" +
                                  run.set.ids[k] + "'");
        }
        run.report.scenarios.push_back(*outcome);
        run.shard_of.push_back(shard->shard.index);
        run.summaries.push_back(scenarioSummary(shard->dir, *outcome));
    }
    checkOneMachineKind(run, shards);
    return run;
}

std::string mergedMarkdown(const MergedRun& run) {
    size_t failed = 0, skipped = 0;
    for (const ScenarioOutcome& s : run.report.scenarios) {
        failed += !s.passed();
        skipped += s.skipped;
    }
    std::ostringstream out;
    out << "# Regression report\n\n"
        << run.report.scenarios.size() << " scenarios of set " << run.set.id << " in "
        << run.shard_dirs.size() << " shards: " << failed << " failed, " << skipped << " skipped. "
        << (run.report.passed() ? "Every check passed." : "**Some checks failed.**") << "\n\n```\n"
        << run.report.table() << "```\n";
    std::ostringstream notes;
    for (const ScenarioOutcome& s : run.report.scenarios) {
        if (!s.note.empty() && !s.skipped) notes << "- " << s.note << "\n";
        for (const auto& c : s.captures) notes << "- picture of the worst frame: `" << c << "`\n";
    }
    if (!notes.str().empty()) out << "\n## Notes\n\n" << notes.str();
    out << "\n## Shards\n\n| shard | folder | scenarios |\n|---|---|---|\n";
    for (size_t i = 0; i < run.shard_dirs.size(); ++i) {
        std::string names;
        for (size_t k = 0; k < run.report.scenarios.size(); ++k) {
            if (run.shard_of[k] == i)
                names += (names.empty() ? "" : ", ") + run.report.scenarios[k].name;
        }
        out << "| " << i << "/" << run.shard_dirs.size() << " | `" << run.shard_dirs[i].string()
            << "` | " << names << " |\n";
    }
    return out.str();
}

Json mergedSummaryJson(const MergedRun& run) {
    Json scenarios = Json::array();
    size_t failed = 0, skipped = 0, checks = 0, failed_checks = 0;
    for (size_t k = 0; k < run.report.scenarios.size(); ++k) {
        const ScenarioOutcome& s = run.report.scenarios[k];
        Json list = Json::array();
        for (const CheckResult& c : s.checks) {
            list.push_back({{"check", c.check},
                            {"expected", c.expected},
                            {"got", c.got},
                            {"passed", c.passed}});
            failed_checks += !c.passed;
        }
        checks += s.checks.size();
        failed += !s.passed();
        skipped += s.skipped;
        scenarios.push_back({{"file", s.scenario},
                             {"name", s.name},
                             {"shard", run.shard_of[k]},
                             {"skipped", s.skipped},
                             {"passed", s.passed()},
                             {"note", s.note},
                             {"checks", list},
                             {"summary", run.summaries[k]}});
    }
    Json shards = Json::array();
    for (size_t i = 0; i < run.shard_dirs.size(); ++i)
        shards.push_back({{"index", i}, {"dir", run.shard_dirs[i].string()}});
    return {{"format", "occsim-regress-merged"},
            {"version", 1},
            {"scenario_set", {{"id", run.set.id}, {"scenarios", run.set.scenarios}}},
            {"shards", shards},
            {"passed", run.report.passed()},
            {"totals",
             {{"scenarios", run.report.scenarios.size()},
              {"failed", failed},
              {"skipped", skipped},
              {"checks", checks},
              {"failed_checks", failed_checks}}},
            {"scenarios", scenarios}};
}

std::string checksTsv(const RegressReport& report) {
    auto cell = [](std::string s) {
        for (char& c : s) {
            if (c == '\t' || c == '\n') c = ' ';
        }
        return s;
    };
    std::string out = "scenario\tcheck\texpected\tgot\tresult\n";
    for (const ScenarioOutcome& s : report.scenarios) {
        if (s.skipped) out += cell(s.name) + "\t-\t-\t-\tskipped: " + cell(s.note) + "\n";
        for (const CheckResult& c : s.checks) {
            out += cell(s.name) + "\t" + cell(c.check) + "\t" + cell(c.expected) + "\t" +
                   cell(c.got) + "\t" + (c.passed ? "pass" : "FAIL") + "\n";
        }
    }
    return out;
}

void writeMergedReport(const std::filesystem::path& out, const MergedRun& run) {
    std::filesystem::create_directories(out);
    writeFileAtomically(out / "junit.xml", junitXml(run.report));
    writeFileAtomically(out / "report.md", mergedMarkdown(run));
    writeFileAtomically(out / "checks.tsv", checksTsv(run.report));
    writeFileAtomically(out / "summary.json", mergedSummaryJson(run).dump(2) + "\n");
}

}  // namespace occsim
