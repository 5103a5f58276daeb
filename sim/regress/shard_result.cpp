#include "sim/regress/shard_result.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "sim/output/atomic_file.h"
#include "sim/regress/junit_reader.h"
#include "sim/regress/result_files.h"
#include "sim/scenario/json_reader.h"

namespace occsim {
namespace {

constexpr const char* kShardFormat = "occsim-regress-shard";

void fnv1a(uint64_t& h, const std::string& bytes) {
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 1099511628211ull;
    }
    h ^= 0xff;  // separator: "ab"+"c" differs from "a"+"bc"
    h *= 1099511628211ull;
}

std::string fileText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    if (in) s << in.rdbuf();
    return s.str();
}

Json outcomeJson(const ScenarioOutcome& s) {
    Json checks = Json::array();
    for (const CheckResult& c : s.checks) {
        Json check = {
            {"check", c.check}, {"expected", c.expected}, {"got", c.got}, {"passed", c.passed}};
        if (!c.algorithm.empty()) check["algorithm"] = c.algorithm;
        checks.push_back(check);
    }
    return {{"file", s.scenario},     {"id", s.id},      {"name", s.name},
            {"skipped", s.skipped},   {"note", s.note},  {"seconds", s.seconds},
            {"captures", s.captures}, {"checks", checks}};
}

std::vector<std::string> stringList(JsonObjectReader& object, const char* key) {
    const JsonArrayReader array = object.array(key);
    std::vector<std::string> out;
    for (size_t i = 0; i < array.size(); ++i) out.push_back(array.at(i).asString());
    return out;
}

ScenarioOutcome readOutcome(const JsonValueReader& value) {
    JsonObjectReader o = value.asObject();
    ScenarioOutcome s;
    s.scenario = o.required("file").asString();
    s.id = o.required("id").asString();
    s.name = o.required("name").asString();
    s.skipped = o.required("skipped").asBool();
    s.note = o.required("note").asString();
    s.seconds = o.required("seconds").asNumber(NumberRange::atLeast(0));
    s.captures = stringList(o, "captures");
    const JsonArrayReader checks = o.array("checks");
    for (size_t i = 0; i < checks.size(); ++i) {
        JsonObjectReader c = checks.at(i).asObject();
        s.checks.push_back({c.required("check").asString(), c.required("expected").asString(),
                            c.required("got").asString(), c.required("passed").asBool(),
                            c.string("algorithm", "")});
        c.finish();
    }
    o.finish();
    return s;
}

// The junit.xml beside shard.json must hold the same scenarios with the same counts: a file cut
// short or edited fails here, not in the merged report.
void checkJunitAgrees(const std::filesystem::path& file, const RegressReport& report) {
    const std::vector<JunitSuite> suites = readJunit(file);
    if (suites.size() != report.scenarios.size()) {
        throw ResultFileError(
            file.string() + ": expected " + std::to_string(report.scenarios.size()) +
            " testsuites (one per scenario in shard.json), got " + std::to_string(suites.size()));
    }
    for (size_t i = 0; i < suites.size(); ++i) {
        const ScenarioOutcome& s = report.scenarios[i];
        size_t failed = 0;
        for (const CheckResult& c : s.checks) failed += !c.passed;
        const size_t tests = s.skipped ? 1 : s.checks.size();
        if (suites[i].name != junitVisibleText(s.name) || suites[i].testcases != tests ||
            suites[i].failures != failed) {
            throw ResultFileError(file.string() + ": testsuite " + std::to_string(i + 1) + " ('" +
                                  suites[i].name + "', " + std::to_string(suites[i].testcases) +
                                  " testcases, " + std::to_string(suites[i].failures) +
                                  " failures) differs from shard.json ('" + s.name + "', " +
                                  std::to_string(tests) + " checks, " + std::to_string(failed) +
                                  " failed)");
        }
    }
}

}  // namespace

ScenarioSet scenarioSetOf(const std::vector<std::filesystem::path>& inputs) {
    ScenarioSet set;
    uint64_t h = 14695981039346656037ull;
    for (const ScenarioFile& s : collectScenarioFiles(inputs)) {
        set.scenarios.push_back(s.file.string());
        set.ids.push_back(s.id);
        fnv1a(h, s.file.string());
        fnv1a(h, fileText(s.file));
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    set.id = buf;
    return set;
}

std::string shardResultJson(const ShardResult& r) {
    Json scenarios = Json::array();
    for (const ScenarioOutcome& s : r.report.scenarios) scenarios.push_back(outcomeJson(s));
    const Json j = {
        {"format", kShardFormat},
        {"version", ShardResult::kFormatVersion},
        {"scenario_set", {{"id", r.set.id}, {"scenarios", r.set.scenarios}, {"ids", r.set.ids}}},
        {"shard", {{"index", r.shard.index}, {"count", r.shard.count}}},
        {"machine", {{"hostname", r.hostname}, {"cpu", r.cpu}}},
        {"scenarios", scenarios}};
    return j.dump(2) + "\n";
}

void writeShardResult(const std::filesystem::path& dir, const ShardResult& result) {
    std::filesystem::create_directories(dir);
    writeFileAtomically(dir / "junit.xml", junitXml(result.report));
    writeFileAtomically(dir / "shard.json", shardResultJson(result));
}

ShardResult readShardResult(const std::filesystem::path& dir) {
    const std::filesystem::path file = dir / "shard.json";
    const std::string name = file.string();
    if (!std::filesystem::is_regular_file(file)) {
        throw ResultFileError(name +
                              ": missing; expected the --out folder of an `occsim regress` run");
    }
    ShardResult r;
    r.dir = dir;
    try {
        const Json root = parseStrictJson(fileText(file), name);
        JsonObjectReader top(root, "", name);
        if (top.string("format", "") != kShardFormat) {
            top.fail("format", std::string("expected \"") + kShardFormat +
                                   "\": not a shard result of occsim regress");
        }
        const JsonValueReader version = top.required("version");
        if (!(version.json().is_number_integer() &&
              version.json() == ShardResult::kFormatVersion)) {
            version.fail("shard result format version " + version.json().dump() +
                         "; this program reads version " +
                         std::to_string(ShardResult::kFormatVersion) +
                         " (rerun the shard with this occsim)");
        }
        JsonObjectReader set = top.object("scenario_set");
        r.set.id = set.required("id").asString();
        r.set.scenarios = stringList(set, "scenarios");
        r.set.ids = stringList(set, "ids");
        if (r.set.ids.size() != r.set.scenarios.size()) {
            set.fail("ids", "expected one id per scenario (" +
                                std::to_string(r.set.scenarios.size()) + "), got " +
                                std::to_string(r.set.ids.size()));
        }
        set.finish();
        JsonObjectReader shard = top.object("shard");
        r.shard.count = static_cast<uint32_t>(shard.requiredUnsignedInteger("count", 1, 1000000));
        r.shard.index =
            static_cast<uint32_t>(shard.requiredUnsignedInteger("index", 0, r.shard.count - 1));
        shard.finish();
        JsonObjectReader machine = top.object("machine");
        r.hostname = machine.required("hostname").asString();
        r.cpu = machine.required("cpu").asString();
        machine.finish();
        const JsonArrayReader scenarios = top.array("scenarios");
        for (size_t i = 0; i < scenarios.size(); ++i)
            r.report.scenarios.push_back(readOutcome(scenarios.at(i)));
        top.finish();
    } catch (const ScenarioError& e) {
        throw ResultFileError(e.what());
    }
    checkJunitAgrees(dir / "junit.xml", r.report);
    return r;
}

Json scenarioSummary(const std::filesystem::path& dir, const ScenarioOutcome& outcome) {
    const std::filesystem::path file = dir / outcome.id / "summary.json";
    if (!outcome.ran()) return nullptr;
    // A scenario that ran and left no summary would drop out of the merged summary unseen.
    if (!std::filesystem::is_regular_file(file)) {
        throw ResultFileError(file.string() + ": missing; " + outcome.scenario +
                              " ran in this shard (shard.json lists its checks); expected its "
                              "summary.json beside every scenario that ran");
    }
    Json summary;
    try {
        summary = parseStrictJson(fileText(file), file.string());
    } catch (const ScenarioError& e) {
        throw ResultFileError(e.what());
    }
    // A summary copied from another scenario's folder would file its figures under this one.
    const Json* block =
        summary.is_object() && summary.contains("scenario") ? &summary["scenario"] : nullptr;
    auto field = [&](const char* key) {
        return block && block->is_object() && block->contains(key) && (*block)[key].is_string()
                   ? (*block)[key].get<std::string>()
                   : std::string("(none)");
    };
    const std::string id = field("id"), name = field("name"), scenario_file = field("file");
    if (id != outcome.id || name != outcome.name || scenario_file != outcome.scenario) {
        throw ResultFileError(file.string() + ": /scenario: the summary of scenario '" + name +
                              "' (id " + id + ", file " + scenario_file + "); expected that of '" +
                              outcome.name + "' (id " + outcome.id + ", file " + outcome.scenario +
                              "), which shard.json files here");
    }
    return summary;
}

}  // namespace occsim
