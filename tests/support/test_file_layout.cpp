// Tests are laid out like the sources (issues 31 and 54): every source of the four libraries has
// a test file named after it in the test folder named like its own (tests/support/file_layout.h),
// so that the test of a file is found by its name and place. The exceptions, each with where its
// code is tested instead, are in tests/support/layout_exceptions.txt.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "file_layout.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

// Source -> where it is tested instead.
std::map<std::string, std::string> exceptions() {
    return testing::readLayoutExceptions(fs::path(OCCSIM_SOURCE_DIR) / "tests" / "support" /
                                         "layout_exceptions.txt");
}

TEST(FileLayout, EverySourceHasATestFileNamedAfterIt) {
    const std::vector<std::string> missing =
        testing::sourcesWithoutTestFile(OCCSIM_SOURCE_DIR, exceptions());
    for (const std::string& source : missing) {
        ADD_FAILURE() << source << " has no "
                      << testing::testFileOf("", source).relative_path().generic_string()
                      << " (write one, or add it to tests/support/layout_exceptions.txt with where "
                         "it is tested)";
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

// The check can fail: a tree with sources and no test files for them names each source, in every
// library the rule covers.
TEST(FileLayout, TheCheckNamesASourceWithoutItsTestFile) {
    const fs::path root =
        fs::temp_directory_path() / ("occsim-file-layout-" + std::to_string(::getpid()));
    fs::remove_all(root);
    const auto write = [&](const fs::path& file) {
        fs::create_directories((root / file).parent_path());
        std::ofstream(root / file) << "\n";
    };
    write("culling/cullers/a_culler.cpp");
    write("culling/cullers/b_culler.cpp");
    write("culling/cullers/b_culler.h");
    write("tests/culling/cullers/test_b_culler.cpp");
    // A test file in another room's folder, or at the old flat place, does not count.
    write("culling/tree/c_tree.cpp");
    write("tests/culling/cullers/test_c_tree.cpp");
    write("tests/test_a_culler.cpp");
    // The other libraries: a render source, a sim layer's, the tuner's; each with its test file
    // in the wrong folder, and one of each with its test file in place.
    write("render/d_context.cpp");
    write("tests/test_d_context.cpp");
    write("render/e_shader.cpp");
    write("tests/render/test_e_shader.cpp");
    write("sim/run/f_runner.cpp");
    write("tests/sim/output/test_f_runner.cpp");
    write("sim/world/g_movers.cpp");
    write("tests/sim/world/test_g_movers.cpp");
    write("tune/h_fit.cpp");
    write("tests/tune/sub/test_h_fit.cpp");
    write("tune/i_design.cpp");
    write("tests/tune/test_i_design.cpp");
    // A folder outside the four libraries is not checked.
    write("examples/plugin/j_example.cpp");
    EXPECT_EQ(testing::sourcesWithoutTestFile(root, {}),
              (std::vector<std::string>{"culling/cullers/a_culler.cpp", "culling/tree/c_tree.cpp",
                                        "render/d_context.cpp", "sim/run/f_runner.cpp",
                                        "tune/h_fit.cpp"}));
    EXPECT_EQ(testing::sourcesWithoutTestFile(
                  root, {{"culling/cullers/a_culler.cpp", "why"}, {"sim/run/f_runner.cpp", "why"}}),
              (std::vector<std::string>{"culling/tree/c_tree.cpp", "render/d_context.cpp",
                                        "tune/h_fit.cpp"}));
    fs::remove_all(root);
}

// The exceptions file: a line without a reason, or a source named twice, is refused with the
// file and line.
TEST(FileLayout, TheExceptionsFileRefusesALineWithoutAReasonAndASourceNamedTwice) {
    const fs::path file = fs::temp_directory_path() /
                          ("occsim-layout-exceptions-" + std::to_string(::getpid()) + ".txt");
    std::ofstream(file) << "# a comment\n\nrender/a.cpp: tested in b\nrender/c.cpp\n";
    try {
        testing::readLayoutExceptions(file);
        ADD_FAILURE() << "a line without a reason was read";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(".txt:4: expected 'source: why'"), std::string::npos)
            << e.what();
    }
    std::ofstream(file) << "render/a.cpp: tested in b\nrender/a.cpp: and in c\n";
    try {
        testing::readLayoutExceptions(file);
        ADD_FAILURE() << "a source named twice was read";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(".txt:2: render/a.cpp is excepted twice"),
                  std::string::npos)
            << e.what();
    }
    std::ofstream(file) << "# a comment\n\nrender/a.cpp: tested in b\n";
    EXPECT_EQ(testing::readLayoutExceptions(file),
              (std::map<std::string, std::string>{{"render/a.cpp", "tested in b"}}));
    fs::remove(file);
}

}  // namespace
}  // namespace occsim
