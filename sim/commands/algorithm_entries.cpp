#include "sim/commands/algorithm_entries.h"

#include <algorithm>
#include <stdexcept>

#include "occsim/culling/contract/input_error.h"
#include "sim/commands/flag_checks.h"

namespace occsim_cli {
namespace {

std::vector<std::string> splitLists(const std::vector<std::string>& lists) {
    std::vector<std::string> names;
    for (const std::string& list : lists) {
        size_t start = 0;
        while (true) {
            const size_t comma = list.find(',', start);
            names.push_back(
                list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
    }
    return names;
}

// The culler a culling file is for: its "tuned_for", else its culling.algorithm; empty for a
// file that names none.
std::string cullerOfFile(const occsim::CullingFile& file) {
    const occsim::Json& j = file.json;
    if (j.contains("tuned_for") && j.at("tuned_for").is_string())
        return j.at("tuned_for").get<std::string>();
    const occsim::Json& culling = j.at("culling");
    if (culling.contains("algorithm") && culling.at("algorithm").is_string())
        return culling.at("algorithm").get<std::string>();
    return "";
}

AlgorithmEntry entryOf(const std::string& flag, const std::string& text) {
    const size_t at = text.find('@');
    AlgorithmEntry e;
    e.algorithm = &algorithmNamed(flag, text.substr(0, at));
    e.label = e.algorithm->name;
    if (at == std::string::npos) return e;
    const std::filesystem::path file = text.substr(at + 1);
    if (file.empty()) {
        throw occsim::InputError(flag + " " + text +
                                 ": no file after '@'; expected NAME@FILE, FILE a culling file "
                                 "such as occtune's tuned.json");
    }
    try {
        e.culling = occsim::readCullingFile(file);
    } catch (const occsim::InputError& error) {
        throw occsim::InputError(flag + " " + text + ": " + error.what());
    }
    const std::string target = cullerOfFile(*e.culling);
    if (target != e.algorithm->name) {
        throw occsim::InputError(
            flag + " " + text + ": " + file.string() +
            (target.empty() ? " names no culler"
                            : " is a culling file for " + target + ", not " + e.algorithm->name) +
            "; expected \"tuned_for\": \"" + e.algorithm->name + "\" or culling.algorithm \"" +
            e.algorithm->name + "\"");
    }
    e.label += "@" + file.stem().string();
    return e;
}

}  // namespace

std::vector<AlgorithmEntry> algorithmEntries(const std::string& flag,
                                             const std::vector<std::string>& lists) {
    std::vector<AlgorithmEntry> out;
    for (const std::string& text : splitLists(lists)) {
        if (text.empty())
            throw occsim::InputError(flag + ": an empty algorithm name (a comma too many?)");
        AlgorithmEntry e = entryOf(flag, text);
        if (std::any_of(out.begin(), out.end(),
                        [&](const AlgorithmEntry& o) { return o.label == e.label; })) {
            throw occsim::InputError(
                flag + ": '" + e.label + "' is listed twice" +
                (e.culling ? " (two files of one name: give them names of their own)" : ""));
        }
        out.push_back(std::move(e));
    }
    return out;
}

std::vector<const occsim::CullerRow*> plainAlgorithms(const std::vector<AlgorithmEntry>& entries) {
    std::vector<const occsim::CullerRow*> out;
    for (const AlgorithmEntry& e : entries) {
        if (!e.culling) out.push_back(e.algorithm);
    }
    return out;
}

bool anyCullingFile(const std::vector<AlgorithmEntry>& entries) {
    return std::any_of(entries.begin(), entries.end(),
                       [](const AlgorithmEntry& e) { return e.culling.has_value(); });
}

std::vector<occsim::RunConfig> entryConfigs(const std::vector<AlgorithmEntry>& entries,
                                            const occsim::Scenario& scenario,
                                            const std::optional<occsim::Sweep>& sweep,
                                            const std::string& ablate) {
    const std::vector<const occsim::CullerRow*> plain = plainAlgorithms(entries);
    const std::vector<occsim::RunConfig> planned =
        plain.empty() ? std::vector<occsim::RunConfig>{}
                      : occsim::planConfigs(plain, scenario.culler, sweep, ablate);
    std::vector<occsim::RunConfig> out;
    for (const AlgorithmEntry& e : entries) {
        if (!e.culling) {
            for (const occsim::RunConfig& c : planned) {
                if (c.algorithm == e.algorithm) out.push_back(c);
            }
            continue;
        }
        occsim::Scenario tuned = scenario;
        occsim::applyCullingFile(*e.culling, tuned);
        out.push_back({e.label, e.algorithm, tuned.culler, e.culling->file.string()});
    }
    return out;
}

}  // namespace occsim_cli
