// The rule that tests are laid out like the sources: every culling/**/*.cpp has a test file named
// after it, tests/test_<stem>.cpp, so that the test of a file is found by its name. A source may
// be excepted, with the reason, where its tests live elsewhere.
#pragma once

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace occsim::testing {

// The sources under `root`/culling without their test file `root`/tests/test_<stem>.cpp, as paths
// relative to `root`, sorted; `excepted` (paths relative to `root`) are left out.
inline std::vector<std::string> sourcesWithoutTestFile(
    const std::filesystem::path& root, const std::map<std::string, std::string>& excepted) {
    namespace fs = std::filesystem;
    std::vector<std::string> missing;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(root / "culling")) {
        if (!e.is_regular_file() || e.path().extension() != ".cpp") continue;
        const std::string relative = e.path().lexically_relative(root).generic_string();
        if (excepted.count(relative)) continue;
        std::string name = "test_";
        name.append(e.path().stem().string()).append(".cpp");
        if (!fs::exists(root / "tests" / name)) missing.push_back(relative);
    }
    std::sort(missing.begin(), missing.end());
    return missing;
}

}  // namespace occsim::testing
