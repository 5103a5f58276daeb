// JUnit files read back (sim/regress/junit_reader.h), as the merge reads each shard's: what
// junitXml writes reads back suite for suite, and every truncation is refused naming the file.
#include <gtest/gtest.h>

#include <string>

#include "merge_files.h"
#include "sim/regress/junit_reader.h"
#include "sim/regress/regress.h"

namespace occsim {
namespace {

using namespace merge_files;

TEST(Junit, ReadsBackWhatJunitXmlWrites) {
    const auto suites = parseJunit(junitXml(wholeReport()), "x.xml");
    ASSERT_EQ(suites.size(), 6u);
    EXPECT_EQ(suites[2].name, "c");
    EXPECT_EQ(suites[2].testcases, 2u);
    EXPECT_EQ(suites[2].failures, 1u);
    EXPECT_EQ(suites[4].skipped, 1u);
}

TEST(Junit, EveryTruncationOfAFileIsRefusedNamingTheFile) {
    const std::string xml = junitXml(wholeReport());
    for (size_t cut = 0; cut + 1 < xml.size(); cut += 7) {
        EXPECT_THROW(
            {
                try {
                    parseJunit(xml.substr(0, cut), "cut.xml");
                } catch (const ResultFileError& e) {
                    EXPECT_EQ(std::string(e.what()).rfind("cut.xml: line ", 0), 0u) << e.what();
                    throw;
                }
            },
            ResultFileError)
            << "cut at " << cut;
    }
    std::string edited = xml;
    edited.replace(edited.find("<testcase"), 9, "<testcaze");
    EXPECT_THROW(parseJunit(edited, "edited.xml"), ResultFileError);
}

}  // namespace
}  // namespace occsim
