// The sample log: batches written whole, read back, and a file that is not one refused by line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tune/errors.h"
#include "tune_fixtures.h"

namespace occsim::tune {
namespace {

using namespace fixtures;

TEST(SampleLog, BatchesAreWrittenWholeAndReadBackAsRatios) {
    const auto file = std::filesystem::temp_directory_path() /
                      ("occtune-log-" + std::to_string(::getpid()) + ".jsonl");
    {
        SampleLog log(file, settings());
        LoggedRun ref{0, true, {2.0 / 3.0}, 20.0, 40.0, 0, {{20.0, 1, 2, 3, 4}}};
        LoggedRun a{0, false, {0.5}, 18.0, 44.0, 0, {{18.0, 1, 2, 3, 4}}};
        log.appendBatch({ref, a});
        // Two references: the samples are ratios to their mean.
        LoggedRun ref2{1, true, {2.0 / 3.0}, 25.0, 50.0, 0, {}};
        LoggedRun ref3{1, true, {2.0 / 3.0}, 35.0, 70.0, 0, {}};
        LoggedRun b{1, false, {1.5}, 33.0, 54.0, 0, {}};
        log.appendBatch({ref2, ref3, b});
    }
    const SampleLog log = SampleLog::read(file);
    EXPECT_EQ(log.batches(), 2u);
    const std::vector<Sample> samples = log.samples();
    ASSERT_EQ(samples.size(), 2u);
    EXPECT_DOUBLE_EQ(samples[0].ratio_mean, 0.9);
    EXPECT_DOUBLE_EQ(samples[0].ratio_p95, 1.1);
    EXPECT_DOUBLE_EQ(samples[1].ratio_mean, 1.1);
    EXPECT_DOUBLE_EQ(samples[1].run->values[0], 1.5);
    EXPECT_DOUBLE_EQ(samples[1].ratio_p95, 0.9);
    // One batch with two references, 25 and 35 ms: log(35 / 25) / sqrt(2).
    EXPECT_NEAR(log.referenceNoise(), std::log(35.0 / 25.0) / std::sqrt(2.0), 1e-12);
    EXPECT_DOUBLE_EQ(log.runs()[0].values[0], 2.0 / 3.0);  // doubles survive the text exactly
    EXPECT_EQ(log.mismatch(settings()), "");
    LogSettings other = settings();
    other.bounds = {{0.1, 1.0}};
    EXPECT_NE(log.mismatch(other).find("--bounds base_time=0.1:2"), std::string::npos);
    other = settings();
    other.scenario_hash = textHash("{ }");
    EXPECT_NE(log.mismatch(other).find("another scenario"), std::string::npos);
    std::filesystem::remove(file);
}

TEST(SampleLog, ALogThatIsNotOneIsBadInputNamingTheLine) {
    const auto file = std::filesystem::temp_directory_path() /
                      ("occtune-bad-" + std::to_string(::getpid()) + ".jsonl");
    std::ofstream(file) << "{\"occtune_sample_log\": 1}\n";
    try {
        SampleLog::read(file);
        FAIL() << "accepted";
    } catch (const TuneInputError& e) {
        EXPECT_NE(std::string(e.what()).find(":1: not an occtune sample log line"),
                  std::string::npos)
            << e.what();
    }
    std::filesystem::remove(file);
}

}  // namespace
}  // namespace occsim::tune
