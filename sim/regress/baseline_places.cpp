#include "sim/regress/baseline_places.h"

#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

namespace occsim {
namespace fs = std::filesystem;
namespace {

// The path that tells two names of one file apart from two files: symlinks and ".." resolved.
fs::path resolved(const fs::path& file) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(fs::absolute(file, ec), ec);
    return ec ? fs::absolute(file).lexically_normal() : p;
}

bool inside(const fs::path& file, const fs::path& folder) {
    const fs::path rel = file.lexically_relative(folder);
    return !rel.empty() && *rel.begin() != ".." && rel != ".";
}

}  // namespace

namespace {

// The file's JSON when it is an occsim baseline; null otherwise.
nlohmann::json baselineJson(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return nullptr;
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_object() && j.contains("format") && j["format"] == "occsim-baseline") return j;
    return nullptr;
}

}  // namespace

bool isOccsimBaselineFile(const fs::path& file) { return !baselineJson(file).is_null(); }

std::string baselineScenarioName(const fs::path& file) {
    const nlohmann::json j = baselineJson(file);
    if (j.is_null() || !j.contains("scenario") || !j["scenario"].is_string()) return {};
    return j["scenario"].get<std::string>();
}

std::vector<std::string> baselinePlaceProblems(const std::vector<BaselinePlace>& places,
                                               const std::vector<fs::path>& scenario_files,
                                               bool update) {
    std::set<fs::path> scenarios;
    for (const fs::path& f : scenario_files) scenarios.insert(resolved(f));
    std::map<fs::path, const BaselinePlace*> owner;
    std::vector<std::string> problems;
    for (const BaselinePlace& p : places) {
        const std::string where =
            p.scenario_file.string() + ": /expect/baseline: " + p.baseline.string();
        const fs::path file = resolved(p.baseline);
        const fs::path folder = resolved(p.scenario_file).parent_path();
        std::error_code ec;
        if (file == resolved(p.scenario_file)) {
            problems.push_back(where +
                               " is the scenario file itself; expected a file of its "
                               "own (default <name>.baseline.json beside the scenario)");
        } else if (scenarios.count(file)) {
            problems.push_back(where +
                               " is a scenario file of this run; expected a file of its "
                               "own (default <name>.baseline.json beside the scenario)");
        } else if (!inside(file, folder)) {
            problems.push_back(where + " lies outside the scenario's folder " + folder.string() +
                               "; expected a file in it or below it");
        } else if (const auto [it, first] = owner.emplace(file, &p); !first) {
            problems.push_back(where + " is also the baseline of " +
                               it->second->scenario_file.string() +
                               "; expected one baseline file per scenario");
        } else if (fs::is_directory(file, ec)) {
            problems.push_back(where +
                               " is a folder; expected a file (default <name>.baseline.json "
                               "beside the scenario)");
        } else if (update && fs::exists(file, ec) && !isOccsimBaselineFile(file)) {
            problems.push_back(where +
                               " exists and is not an occsim baseline file (no \"format\": "
                               "\"occsim-baseline\"); --update overwrites only baselines: "
                               "move it, or name another file");
        } else if (update && !p.scenario_name.empty() && fs::exists(file, ec)) {
            const std::string recorded = baselineScenarioName(file);
            if (!recorded.empty() && recorded != p.scenario_name) {
                problems.push_back(where + " is the baseline of the scenario '" + recorded +
                                   "', not '" + p.scenario_name +
                                   "'; --update never writes over another scenario's "
                                   "baseline: name another file");
            }
        }
    }
    return problems;
}

}  // namespace occsim
