// The history of regression runs (sim/regress/history.h): an entry written and read back, and one
// made now from a run's summaries with the machine, the commit and every algorithm's figures.
// Another format version refused by the commands: tests/system/test_history.cpp.
#include <gtest/gtest.h>

#include <filesystem>

#include "merge_files.h"
#include "sim/regress/history.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;
using namespace merge_files;

TEST(History, AnEntryReadsBackAsWritten) {
    const fs::path dir = historyOf("roundtrip", {entry("2025-01-01T00:00:00Z", "m", 2.5)});
    const auto runs = readHistory(dir);
    ASSERT_EQ(runs.size(), 1u);
    EXPECT_EQ(historyEntryJson(runs[0]), historyEntryJson(entry("2025-01-01T00:00:00Z", "m", 2.5)));
    EXPECT_EQ(runs[0].scenarios.at("s").at("statistical").speedup, 2.5);
}

TEST(History, AnEntryMadeNowRecordsMachineCommitAndFigures) {
    const Json summary =
        Json::parse(R"json({"machine": {"backend": "osmesa", "gl_renderer": "llvmpipe (LLVM 15)"},
        "algorithms": [{"configuration": "vfc", "speedup_over_vfc": 1.0, "queries_per_frame": 0,
                        "objects_per_frame": 100, "error": {"pixels_per_frame_mean": 0}},
                       {"configuration": "chc", "speedup_over_vfc": 1.8, "queries_per_frame": 12.5,
                        "objects_per_frame": 30, "error": {"pixels_per_frame_mean": 0.5}}]})json");
    const HistoryEntry e = historyEntryNow({{"s", summary}}, "abc123");
    EXPECT_EQ(e.commit, "abc123");
    EXPECT_EQ(e.backend, "osmesa");
    EXPECT_EQ(e.renderer, "llvmpipe (LLVM 15)");
    EXPECT_FALSE(e.hostname.empty());
    EXPECT_FALSE(e.cpu.empty());
    EXPECT_EQ(e.date.size(), 20u) << e.date;
    EXPECT_EQ(e.scenarios.at("s").at("chc").speedup, 1.8);
    EXPECT_EQ(e.scenarios.at("s").at("chc").queries, 12.5);
    EXPECT_EQ(e.scenarios.at("s").at("chc").error, 0.5);
}

}  // namespace
}  // namespace occsim
