// junit.xml as regress and merge write it (sim/regress/junit_writer.cpp, declared in
// sim/regress/regress.h): a failed check names its own culler's pictures, before and after a
// shard's file; control characters never break the XML.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "merge_files.h"
#include "sim/regress/junit_reader.h"
#include "sim/regress/regress.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using namespace merge_files;

// A failed check's entry names the pictures of its own culler's worst frame, not another's; the
// culler a check is about survives a shard's file, so a merged junit.xml says the same.
TEST(Junit, AFailedChecksEntryListsOnlyItsOwnCullersPictures) {
    ShardResult r;
    r.set = sixScenarios();
    r.set.scenarios = {"scenarios/a.json"};
    r.set.ids = {"a"};
    r.shard = {0, 1};
    ScenarioOutcome o = outcomeOf("scenarios/a.json");
    o.checks = {
        {"zero error pixels: statistical", "0 on every frame", "4 px", false, "statistical"},
        {"zero error pixels: statistical+", "0 on every frame", "9 px", false, "statistical+"},
        {"frame time chc / vfc", "<= 1.00", "1.20", false}};
    o.captures = {"out/a/worst-error-statistical-frame-00003.png",
                  "out/a/worst-error-statistical+-frame-00007.png"};
    r.report.scenarios = {o};
    auto failureOf = [](const std::string& xml, const std::string& check) {
        const size_t at = xml.find("name=\"" + check + "\"><failure");
        EXPECT_NE(at, std::string::npos) << check << " in " << xml;
        return xml.substr(at, xml.find("</failure>", at) - at);
    };
    for (const RegressReport& report : {r.report, [&] {
                                            const fs::path dir = freshDir("junit-pictures");
                                            writeShardResult(dir / "shard", r);
                                            return readShardResult(dir / "shard").report;
                                        }()}) {
        const std::string xml = junitXml(report);
        const std::string plain = failureOf(xml, "zero error pixels: statistical");
        EXPECT_NE(plain.find("worst-error-statistical-frame-00003.png"), std::string::npos);
        EXPECT_EQ(plain.find("worst-error-statistical+-frame"), std::string::npos) << plain;
        const std::string plus = failureOf(xml, "zero error pixels: statistical+");
        EXPECT_NE(plus.find("worst-error-statistical+-frame-00007.png"), std::string::npos);
        EXPECT_EQ(plus.find("worst-error-statistical-frame"), std::string::npos) << plus;
        EXPECT_EQ(failureOf(xml, "frame time chc / vfc").find("capture:"), std::string::npos);
    }
}

// A name with a control character is written so that junit.xml stays well-formed XML, and reads
// back as the merge compares it.
TEST(Junit, AControlCharacterInANameKeepsTheFileWellFormed) {
    RegressReport report = wholeReport();
    report.scenarios[0].name =
        "a\x01"
        "b\tc";
    report.scenarios[0].checks[0].got = "bell\x07";
    const std::string xml = junitXml(report);
    EXPECT_EQ(xml.find('\x01'), std::string::npos);
    EXPECT_EQ(xml.find('\x07'), std::string::npos);
    const auto suites = parseJunit(xml, "x.xml");
    EXPECT_EQ(suites[0].name,
              "a\\x01"
              "b\tc");
    EXPECT_EQ(suites[0].name, junitVisibleText(report.scenarios[0].name));
}

}  // namespace
}  // namespace occsim
