#include "sim/regress/scenario_identity.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include "occsim/culling/contract/input_error.h"
#include "sim/output/run_folder.h"
#include "sim/regress/regress.h"

namespace occsim {
namespace fs = std::filesystem;
namespace {

bool isScenarioFile(const fs::path& p) {
    return p.extension() == ".json" && !p.filename().string().ends_with(".baseline.json");
}

// A folder an occsim run wrote (a run folder, a regress --out): its summary.json and shard.json
// are results, not scenarios, and a regress whose --out lies inside its input must not take them.
bool isOutputFolder(const fs::path& folder) {
    std::error_code ec;
    return fs::exists(folder / kRunMarker, ec) || fs::exists(folder / kRegressMarker, ec);
}

// The path that tells two names of one file apart from two files: symlinks and "." resolved.
fs::path identityOf(const fs::path& file) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(file, ec);
    return ec ? fs::absolute(file).lexically_normal() : p;
}

void addEscaped(std::string& out, unsigned char c) {
    char buf[4];
    std::snprintf(buf, sizeof buf, "%%%02X", c);
    out += buf;
}

}  // namespace

std::string scenarioId(const fs::path& relative) {
    fs::path p = relative;
    if (p.extension() == ".json") p.replace_extension();
    std::string id;
    for (const fs::path& part : p) {
        const std::string name = part.string();
        if (name.empty() || name == ".") continue;
        if (!id.empty()) id += '+';
        for (size_t i = 0; i < name.size(); ++i) {
            const unsigned char c = static_cast<unsigned char>(name[i]);
            const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                               (c >= '0' && c <= '9') || c == '-' || c == '_' ||
                               (c == '.' && i > 0);
            if (plain) {
                id += static_cast<char>(c);
            } else {
                addEscaped(id, c);
            }
        }
    }
    return id.empty() ? "%2E" : id;
}

std::vector<ScenarioFile> collectScenarioFiles(const std::vector<fs::path>& inputs) {
    std::vector<ScenarioFile> found;
    for (const fs::path& input : inputs) {
        std::error_code ec;
        if (!fs::is_directory(input, ec)) {
            // A missing file is reported when it is parsed, as the scenario's failed check.
            found.push_back({input, scenarioId(input.filename())});
            continue;
        }
        std::vector<fs::path> files;
        for (auto it = fs::recursive_directory_iterator(input);
             it != fs::recursive_directory_iterator(); ++it) {
            if (it->is_directory() && isOutputFolder(it->path())) {
                it.disable_recursion_pending();
            } else if (it->is_regular_file() && isScenarioFile(it->path())) {
                files.push_back(it->path());
            }
        }
        for (const fs::path& file : files)
            found.push_back({file, scenarioId(file.lexically_relative(input))});
    }
    std::sort(found.begin(), found.end(),
              [](const ScenarioFile& a, const ScenarioFile& b) { return a.file < b.file; });

    std::vector<std::string> problems;
    std::map<fs::path, const ScenarioFile*> by_identity;
    std::map<std::string, const ScenarioFile*> by_id;
    std::vector<ScenarioFile> unique;
    for (const ScenarioFile& s : found) {
        const auto [same_file, new_file] = by_identity.emplace(identityOf(s.file), &s);
        if (!new_file) {
            if (same_file->second->file != s.file) {
                problems.push_back(s.file.string() + ": the same file as " +
                                   same_file->second->file.string() +
                                   "; expected each scenario file given once");
            } else {
                problems.push_back(s.file.string() +
                                   ": given twice (by two of the paths given); expected each "
                                   "scenario file given once");
            }
            continue;
        }
        const auto [same_id, new_id] = by_id.emplace(s.id, &s);
        if (!new_id) {
            problems.push_back(s.file.string() + " and " + same_id->second->file.string() +
                               ": both would write the results folder '" + s.id +
                               "'; expected scenario files that differ in their path below the "
                               "folder given (give their common folder instead)");
        }
    }
    if (!problems.empty()) {
        std::string message;
        for (const std::string& p : problems) message += (message.empty() ? "" : "\n") + p;
        throw InputError(message);
    }
    return found;
}

std::vector<ScenarioFile> shardOf(const std::vector<ScenarioFile>& all, const Shard& shard) {
    std::vector<ScenarioFile> mine;
    for (size_t i = 0; i < all.size(); ++i) {
        if (i % shard.count == shard.index) mine.push_back(all[i]);
    }
    return mine;
}

}  // namespace occsim
