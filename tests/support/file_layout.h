// The rule that tests are laid out like the sources: every culling/<room>/**/*.cpp has a test file
// named after it in its room's test folder, tests/culling/<room>/test_<stem>.cpp, so that the test
// of a file is found by its name and place. A source may be excepted, with the reason, where its
// tests live elsewhere.
#pragma once

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace occsim::testing {

// Where the test file of `source` (a path relative to `root`, culling/<room>/...) belongs.
inline std::filesystem::path testFileOf(const std::filesystem::path& root,
                                        const std::filesystem::path& source) {
    const std::filesystem::path in_culling = source.lexically_relative("culling");
    std::string name = "test_";
    name.append(source.stem().string()).append(".cpp");
    return root / "tests" / "culling" / *in_culling.begin() / name;
}

// The sources under `root`/culling without their test file (testFileOf), as paths relative to
// `root`, sorted; `excepted` (paths relative to `root`) are left out.
inline std::vector<std::string> sourcesWithoutTestFile(
    const std::filesystem::path& root, const std::map<std::string, std::string>& excepted) {
    namespace fs = std::filesystem;
    std::vector<std::string> missing;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(root / "culling")) {
        if (!e.is_regular_file() || e.path().extension() != ".cpp") continue;
        const std::string relative = e.path().lexically_relative(root).generic_string();
        if (excepted.count(relative)) continue;
        if (!fs::exists(testFileOf(root, relative))) missing.push_back(relative);
    }
    std::sort(missing.begin(), missing.end());
    return missing;
}

}  // namespace occsim::testing
