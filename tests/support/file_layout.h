// The rule that tests are laid out like the sources: every source of the four libraries has a test
// file named after it in the test folder named like its own folder, so that the test of a file is
// found by its name and place:
//   culling/<room>/**/<unit>.cpp  ->  tests/culling/<room>/test_<unit>.cpp
//   render/<unit>.cpp             ->  tests/render/test_<unit>.cpp
//   sim/<layer>/<unit>.cpp        ->  tests/sim/<layer>/test_<unit>.cpp
//   tune/<unit>.cpp               ->  tests/tune/test_<unit>.cpp
// A source may be excepted, with the reason, where its tests live elsewhere
// (tests/support/layout_exceptions.txt).
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace occsim::testing {

// The libraries whose sources the rule covers, as folders of the repository.
inline const std::vector<std::string>& laidOutLibraries() {
    static const std::vector<std::string> libraries = {"culling", "render", "sim", "tune"};
    return libraries;
}

// Where the test file of `source` (a path relative to `root`, in one of laidOutLibraries())
// belongs: the culling library's rooms hold their nested folders' tests too; elsewhere the test
// folder is named like the source's own.
inline std::filesystem::path testFileOf(const std::filesystem::path& root,
                                        const std::filesystem::path& source) {
    std::string name = "test_";
    name.append(source.stem().string()).append(".cpp");
    std::filesystem::path folder = source.parent_path();
    if (*source.begin() == "culling") {
        const std::filesystem::path in_culling = source.lexically_relative("culling");
        folder = std::filesystem::path("culling") / *in_culling.begin();
    }
    return root / "tests" / folder / name;
}

// The sources of laidOutLibraries() under `root` without their test file (testFileOf), as paths
// relative to `root`, sorted; `excepted` (paths relative to `root`) are left out. A library
// folder `root` lacks is skipped.
inline std::vector<std::string> sourcesWithoutTestFile(
    const std::filesystem::path& root, const std::map<std::string, std::string>& excepted) {
    namespace fs = std::filesystem;
    std::vector<std::string> missing;
    for (const std::string& library : laidOutLibraries()) {
        if (!fs::is_directory(root / library)) continue;
        for (const fs::directory_entry& e : fs::recursive_directory_iterator(root / library)) {
            if (!e.is_regular_file() || e.path().extension() != ".cpp") continue;
            const std::string relative = e.path().lexically_relative(root).generic_string();
            if (excepted.count(relative)) continue;
            if (!fs::exists(testFileOf(root, relative))) missing.push_back(relative);
        }
    }
    std::sort(missing.begin(), missing.end());
    return missing;
}

// The exceptions file: one `source: why` a line; blank lines and lines starting with '#' are
// skipped. Throws std::runtime_error naming the file and line for a line without both parts or a
// source named twice.
inline std::map<std::string, std::string> readLayoutExceptions(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file.string() + ": cannot be read");
    std::map<std::string, std::string> exceptions;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (line.empty() || line[0] == '#') continue;
        const std::string::size_type colon = line.find(": ");
        const std::string where = file.string() + ":" + std::to_string(number);
        if (colon == std::string::npos || colon == 0 || colon + 2 >= line.size()) {
            throw std::runtime_error(where + ": expected 'source: why', got '" + line + "'");
        }
        const std::string source = line.substr(0, colon);
        if (!exceptions.emplace(source, line.substr(colon + 2)).second) {
            throw std::runtime_error(where + ": " + source + " is excepted twice");
        }
    }
    return exceptions;
}

}  // namespace occsim::testing
