// report.md names the culler tuned and whose values it started from.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tune/report.h"
#include "tune_fixtures.h"

namespace occsim::tune {
namespace {

using namespace fixtures;

// A finished session's result with every parameter kept at the reference, enough to format.
TuneResult keptResult(const CullerRow& algorithm, const TuneOptions& o, const SampleLog& log) {
    TuneResult r;
    r.options = &o;
    r.log = &log;
    r.scenario_name = "teapots-small";
    r.space = parseParameterSpace(algorithm, "", {});
    for (const TunableParameter& p : r.space.parameters) r.tuned_values.push_back(p.paper_value);
    r.kept_at_paper.assign(r.space.size(), true);
    r.bounds_hit.assign(r.space.size(), "");
    ConfirmationRow row;
    row.variant = "fitted (seed 7)";
    row.same_setting = true;
    r.confirmation = {row};
    r.verdict = judgeConfirmation(r.confirmation, r.reference_noise, referenceName(algorithm));
    return r;
}

// The report names the culler tuned; "paper" is said of the statistical culler's values alone,
// any other culler's are its defaults.
TEST(Report, NamesTheCullerTunedAndCallsOnlyTheStatisticalCullersValuesThePapers) {
    const TuneOptions o;
    const SampleLog log(std::filesystem::temp_directory_path() / "unused-samples.jsonl",
                        settings());
    const std::string plus = reportMarkdown(keptResult(*findCuller("statistical+"), o, log));
    EXPECT_NE(plus.find("# Tuning the statistical+ culler on teapots-small"), std::string::npos)
        << plus;
    EXPECT_EQ(plus.find("paper"), std::string::npos) << plus;
    EXPECT_NE(plus.find("kept at the defaults"), std::string::npos) << plus;
    EXPECT_NE(plus.find("| parameter | default | tuned |"), std::string::npos) << plus;
    const std::string plus_table =
        confirmationTable(keptResult(*findCuller("statistical+"), o, log));
    EXPECT_NE(plus_table.find("missed: tuned/default"), std::string::npos) << plus_table;

    const std::string paper = reportMarkdown(keptResult(statistical(), o, log));
    EXPECT_NE(paper.find("# Tuning the statistical culler on teapots-small"), std::string::npos)
        << paper;
    EXPECT_NE(paper.find("kept at the paper's values"), std::string::npos) << paper;
    EXPECT_NE(paper.find("| parameter | paper | tuned |"), std::string::npos) << paper;
}

}  // namespace
}  // namespace occsim::tune
