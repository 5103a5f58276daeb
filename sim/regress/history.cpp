#include "sim/regress/history.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>

#include "sim/output/atomic_file.h"
#include "sim/regress/result_files.h"

namespace occsim {
namespace {

constexpr const char* kHistoryFormat = "occsim-history";

std::string readAll(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string trimmed(std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    size_t i = 0;
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    return s.substr(i);
}

std::string gitHead() {
    FILE* pipe = popen("git rev-parse HEAD 2>/dev/null", "r");
    if (!pipe) return "";
    std::array<char, 128> buf{};
    std::string out;
    while (fgets(buf.data(), buf.size(), pipe)) out += buf.data();
    pclose(pipe);
    return trimmed(out);
}

std::string commitNow(const std::string& given) {
    if (!given.empty()) return given;
    for (const char* name : {"OCCSIM_COMMIT", "GITHUB_SHA", "CI_COMMIT_SHA"}) {
        if (const char* v = std::getenv(name); v && *v) return v;
    }
    const std::string head = gitHead();
    return head.empty() ? "unknown" : head;
}

std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

double numberOr(const Json& j, const char* key, double fallback) {
    return j.contains(key) && j.at(key).is_number() ? j.at(key).get<double>() : fallback;
}

}  // namespace

std::string thisHostName() {
    char buf[256] = {};
    if (gethostname(buf, sizeof buf - 1) != 0) return "unknown";
    return buf;
}

std::string thisCpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) return trimmed(line.substr(colon + 1));
        }
    }
    return "unknown";
}

std::string HistoryEntry::series() const {
    return hostname + "; " + cpu + "; " + renderer + "; " + backend;
}

HistoryEntry historyEntryNow(const std::vector<std::pair<std::string, Json>>& summaries,
                             const std::string& commit) {
    HistoryEntry e;
    e.commit = commitNow(commit);
    e.date = utcNow();
    e.hostname = thisHostName();
    e.cpu = thisCpuModel();
    for (const auto& [scenario, summary] : summaries) {
        if (summary.contains("machine") && e.backend.empty()) {
            const Json& m = summary.at("machine");
            e.backend = m.value("backend", "");
            e.renderer = m.value("gl_renderer", "");
        }
        if (!summary.contains("algorithms")) continue;
        for (const Json& a : summary.at("algorithms")) {
            AlgorithmFigures f;
            if (a.contains("speedup_over_vfc")) f.speedup = numberOr(a, "speedup_over_vfc", 0);
            f.queries = numberOr(a, "queries_per_frame", 0);
            f.objects = numberOr(a, "objects_per_frame", 0);
            if (a.contains("error")) f.error = numberOr(a.at("error"), "pixels_per_frame_mean", 0);
            e.scenarios[scenario][a.value("configuration", "?")] = f;
        }
    }
    return e;
}

std::string historyEntryJson(const HistoryEntry& e) {
    Json scenarios = Json::object();
    for (const auto& [scenario, algorithms] : e.scenarios) {
        for (const auto& [name, f] : algorithms) {
            scenarios[scenario][name] = {
                {"speedup_over_vfc", f.speedup ? Json(*f.speedup) : Json(nullptr)},
                {"queries_per_frame", f.queries},
                {"objects_per_frame", f.objects},
                {"error_pixels_per_frame", f.error}};
        }
    }
    const Json j = {
        {"format", kHistoryFormat},
        {"version", HistoryEntry::kFormatVersion},
        {"commit", e.commit},
        {"date", e.date},
        {"machine", {{"hostname", e.hostname}, {"cpu", e.cpu}, {"renderer", e.renderer}}},
        {"backend", e.backend},
        {"scenarios", scenarios}};
    return j.dump(2) + "\n";
}

HistoryEntry readHistoryEntry(const std::filesystem::path& file) {
    const std::string name = file.string();
    HistoryEntry e;
    e.file = file.filename().string();
    try {
        const Json root = parseStrictJson(readAll(file), name);
        JsonObjectReader top(root, "", name);
        if (top.string("format", "") != kHistoryFormat) {
            top.fail("format", std::string("expected \"") + kHistoryFormat +
                                   "\": not an occsim history entry");
        }
        const JsonValueReader version = top.required("version");
        if (!(version.json().is_number_integer() &&
              version.json() == HistoryEntry::kFormatVersion)) {
            version.fail("history format version " + version.json().dump() +
                         "; this program reads version " +
                         std::to_string(HistoryEntry::kFormatVersion) +
                         " (keep each version's entries in a folder of their own)");
        }
        e.commit = top.required("commit").asString();
        e.date = top.required("date").asString();
        JsonObjectReader machine = top.object("machine");
        e.hostname = machine.required("hostname").asString();
        e.cpu = machine.required("cpu").asString();
        e.renderer = machine.required("renderer").asString();
        machine.finish();
        e.backend = top.required("backend").asString();
        const JsonValueReader scenarios_value = top.required("scenarios");
        JsonObjectReader scenarios = scenarios_value.asObject();
        for (const auto& s : scenarios_value.json().items()) {
            const JsonValueReader algorithms_value = scenarios.required(s.key());
            JsonObjectReader algorithms = algorithms_value.asObject();
            for (const auto& a : algorithms_value.json().items()) {
                JsonObjectReader fig = algorithms.required(a.key()).asObject();
                AlgorithmFigures f;
                const JsonValueReader speedup = fig.required("speedup_over_vfc");
                if (!speedup.json().is_null())
                    f.speedup = speedup.asNumber(NumberRange::atLeast(0));
                f.queries = fig.requiredNumber("queries_per_frame", NumberRange::atLeast(0));
                f.objects = fig.requiredNumber("objects_per_frame", NumberRange::atLeast(0));
                f.error = fig.requiredNumber("error_pixels_per_frame", NumberRange::atLeast(0));
                fig.finish();
                e.scenarios[s.key()][a.key()] = f;
            }
            algorithms.finish();
        }
        scenarios.finish();
        top.finish();
    } catch (const ScenarioError& err) {
        throw ResultFileError(err.what());
    }
    return e;
}

std::vector<HistoryEntry> readHistory(const std::filesystem::path& dir) {
    if (!std::filesystem::is_directory(dir)) {
        throw ResultFileError(
            dir.string() +
            ": no such folder; expected a history folder (occsim regress --history)");
    }
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.is_regular_file() && entry.path().extension() == ".json")
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    std::vector<HistoryEntry> entries;
    for (const auto& f : files) entries.push_back(readHistoryEntry(f));
    std::stable_sort(entries.begin(), entries.end(),
                     [](const HistoryEntry& a, const HistoryEntry& b) { return a.date < b.date; });
    return entries;
}

void checkHistoryFolder(const std::filesystem::path& dir) {
    if (!std::filesystem::exists(dir)) return;  // created by the first entry
    if (!std::filesystem::is_directory(dir)) {
        throw ResultFileError(dir.string() +
                              ": is a file; expected a history folder (created when missing)");
    }
    readHistory(dir);
}

std::filesystem::path appendHistory(const std::filesystem::path& dir, const HistoryEntry& entry) {
    checkHistoryFolder(dir);
    std::filesystem::create_directories(dir);
    std::string stem;
    for (char c : entry.date) {
        if (std::isalnum(static_cast<unsigned char>(c))) stem += c;
    }
    stem.push_back('-');
    stem.append(safeFileName(entry.commit.substr(0, 12)));
    std::filesystem::path file = dir / (stem + ".json");
    for (int n = 2; std::filesystem::exists(file); ++n)
        file = dir / (stem + "-" + std::to_string(n) + ".json");
    writeFileAtomically(file, historyEntryJson(entry));
    return file;
}

}  // namespace occsim
