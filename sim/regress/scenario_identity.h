// One identity per scenario of a regression run (docs/regression.md "Where results go"): the
// scenario file's path relative to the input it was found under (a folder given to regress), or
// its file name (a file given), made one safe path component. regress writes the scenario's
// folder under it, shard.json and summary.json carry it, merge finds the folder by it and history
// files the figures under it, so no two scenarios can trade or share results.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace occsim {

struct Shard;

struct ScenarioFile {
    std::filesystem::path file;  // as found under the inputs
    std::string id;              // scenarioId() of its path relative to its input
    bool operator==(const ScenarioFile&) const = default;
};

// `relative` without its .json extension, its folders joined by '+', every byte outside
// [A-Za-z0-9._-] (and a leading '.') written as %XX: "paper/city.json" -> "paper+city",
// "ß.json" -> "%C3%9F". Distinct relative paths give distinct ids.
std::string scenarioId(const std::filesystem::path& relative);

// The scenario files under the inputs (files as given; folders searched recursively for *.json,
// skipping *.baseline.json and every folder an occsim run wrote, which holds a run or regress
// marker), sorted by path, each with its id. Throws InputError, one line per problem, before
// anything runs: one file reached twice (by two inputs, or two paths), two files whose ids are
// equal (same-named files given from two folders).
std::vector<ScenarioFile> collectScenarioFiles(const std::vector<std::filesystem::path>& inputs);

// This shard's share of `all`: every count-th from index.
std::vector<ScenarioFile> shardOf(const std::vector<ScenarioFile>& all, const Shard& shard);

}  // namespace occsim
