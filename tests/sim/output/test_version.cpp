// Which occsim this is (sim/output/version.h): the version CMakeLists.txt declares, the commit the
// build was configured from, and the line --version prints.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sim/output/version.h"

namespace occsim {
namespace {

TEST(Version, TheVersionIsTheOneCMakeListsDeclares) {
    std::ifstream in(std::filesystem::path(OCCSIM_SOURCE_DIR) / "CMakeLists.txt");
    std::stringstream text;
    text << in.rdbuf();
    const std::string cmake = text.str();
    const std::string key = "project(occsim VERSION ";
    const size_t at = cmake.find(key);
    ASSERT_NE(at, std::string::npos);
    const size_t from = at + key.size();
    EXPECT_EQ(std::string(occsimVersion()), cmake.substr(from, cmake.find(' ', from) - from));
}

// `git describe --always --dirty`: a hash, or a tag with the commits since and the hash, "-dirty"
// after either. (No std::regex: GCC 12 warns falsely inside <regex> under the sanitizers.)
TEST(Version, TheCommitIsAnAbbreviatedHashOrUnknown) {
    std::string commit = occsimCommit();
    if (commit == "unknown") return;
    const std::string dirty = "-dirty";
    if (commit.size() > dirty.size() && commit.ends_with(dirty))
        commit.resize(commit.size() - dirty.size());
    if (const size_t g = commit.rfind("-g"); g != std::string::npos) commit.erase(0, g + 2);
    EXPECT_GE(commit.size(), 7u) << occsimCommit();
    EXPECT_LE(commit.size(), 40u) << occsimCommit();
    EXPECT_EQ(commit.find_first_not_of("0123456789abcdef"), std::string::npos) << occsimCommit();
}

TEST(Version, TheLineNamesTheProgramTheVersionAndTheCommit) {
    EXPECT_EQ(versionLine("occtune"),
              std::string("occtune ") + occsimVersion() + " (commit " + occsimCommit() + ")");
}

}  // namespace
}  // namespace occsim
