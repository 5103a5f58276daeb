// Which occsim this is (sim/output/version.h): the version CMakeLists.txt declares, the commit the
// build was configured from, and the line --version prints.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "sim/output/version.h"

namespace occsim {
namespace {

TEST(Version, TheVersionIsTheOneCMakeListsDeclares) {
    std::ifstream in(std::filesystem::path(OCCSIM_SOURCE_DIR) / "CMakeLists.txt");
    std::stringstream text;
    text << in.rdbuf();
    std::smatch declared;
    const std::string cmake = text.str();
    ASSERT_TRUE(
        std::regex_search(cmake, declared, std::regex(R"(project\(occsim VERSION ([0-9.]+))")));
    EXPECT_EQ(std::string(occsimVersion()), declared[1].str());
}

// `git describe --always --dirty`: a hash, or a tag with the commits since and the hash.
TEST(Version, TheCommitIsAnAbbreviatedHashOrUnknown) {
    const std::string commit = occsimCommit();
    EXPECT_TRUE(commit == "unknown" ||
                std::regex_match(commit, std::regex("([^ ]+-g)?[0-9a-f]{7,40}(-dirty)?")))
        << commit;
}

TEST(Version, TheLineNamesTheProgramTheVersionAndTheCommit) {
    EXPECT_EQ(versionLine("occtune"),
              std::string("occtune ") + occsimVersion() + " (commit " + occsimCommit() + ")");
}

}  // namespace
}  // namespace occsim
