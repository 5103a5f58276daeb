// Tests are laid out like the sources (issues 31 and 54): every culling/<room>/**/*.cpp has
// tests/culling/<room>/test_<stem>.cpp holding its tests, so that the test of a file is found by
// its name and place. The exceptions below are the sources whose behaviour is tested elsewhere,
// each with where and why.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "file_layout.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

// Source -> why it has no test file of its own.
const std::map<std::string, std::string>& exceptions() {
    static const std::map<std::string, std::string> e = {
        {"culling/registry/registry_text.cpp",
         "the text of `occsim cullers`: tested whole, against docs/cullers.md, by "
         "Cli.TheCullersPageIsTheRegistrysOwnOutput and PluginCli.OccsimCullersListsAPluginsCuller"
         "AndItsOptions (they need the occsim executable)"},
        // Not yet split out of test_masked_culler.cpp, which tests the three together (its
        // property tests share one generator of random scenes); a debt, named here.
        {"culling/raster/masked_depth_buffer.cpp",
         "in test_masked_culler.cpp: MaskedDepthBuffer.* (not yet split out)"},
        {"culling/raster/masked_kernels.cpp",
         "in test_masked_culler.cpp: MaskedDepthBuffer.TheAvx2KernelsGiveThePlainBuffer"},
        {"culling/testing/triangle_raster_device.cpp",
         "the exact reference of test_masked_culler.cpp's property tests (MaskedProperty.*)"},
    };
    return e;
}

TEST(FileLayout, EveryCullingSourceHasATestFileNamedAfterIt) {
    const std::vector<std::string> missing =
        testing::sourcesWithoutTestFile(OCCSIM_SOURCE_DIR, exceptions());
    for (const std::string& source : missing) {
        ADD_FAILURE() << source << " has no "
                      << testing::testFileOf("", source).relative_path().generic_string()
                      << " (write one, or add it to the exceptions with the reason)";
    }
}

TEST(FileLayout, EachExceptionIsASourceThatStillLacksItsTestFile) {
    const fs::path root(OCCSIM_SOURCE_DIR);
    for (const auto& [source, why] : exceptions()) {
        EXPECT_TRUE(fs::exists(root / source)) << source << " is gone: drop its exception";
        EXPECT_FALSE(fs::exists(testing::testFileOf(root, source)))
            << source << " has its test file now: drop its exception";
        EXPECT_FALSE(why.empty()) << source;
    }
}

// The check can fail: a tree with a source and no test file for it names the source.
TEST(FileLayout, TheCheckNamesASourceWithoutItsTestFile) {
    const fs::path root =
        fs::temp_directory_path() / ("occsim-file-layout-" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "culling" / "cullers");
    fs::create_directories(root / "culling" / "tree");
    fs::create_directories(root / "tests" / "culling" / "cullers");
    std::ofstream(root / "culling" / "cullers" / "a_culler.cpp") << "\n";
    std::ofstream(root / "culling" / "cullers" / "b_culler.cpp") << "\n";
    std::ofstream(root / "culling" / "cullers" / "b_culler.h") << "\n";
    std::ofstream(root / "tests" / "culling" / "cullers" / "test_b_culler.cpp") << "\n";
    // A test file in another room's folder, or at the old flat place, does not count.
    std::ofstream(root / "culling" / "tree" / "c_tree.cpp") << "\n";
    std::ofstream(root / "tests" / "culling" / "cullers" / "test_c_tree.cpp") << "\n";
    std::ofstream(root / "tests" / "test_a_culler.cpp") << "\n";
    EXPECT_EQ(
        testing::sourcesWithoutTestFile(root, {}),
        (std::vector<std::string>{"culling/cullers/a_culler.cpp", "culling/tree/c_tree.cpp"}));
    EXPECT_EQ(testing::sourcesWithoutTestFile(root, {{"culling/cullers/a_culler.cpp", "why"}}),
              (std::vector<std::string>{"culling/tree/c_tree.cpp"}));
    fs::remove_all(root);
}

}  // namespace
}  // namespace occsim
