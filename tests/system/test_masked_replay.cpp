// `occsim masked-replay` as a user runs it on the frames recorded by Intel's Masked Occlusion
// Culling (scenarios/assets/moc): every layout printed, the picture and the summary written, bad
// input one line and exit 2. The replay itself: tests/sim/run/test_masked_replay.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "shell_command.h"
#include "sim/run/masked_replay.h"

namespace occsim {
namespace {

const std::filesystem::path kMoc =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/assets/moc";

std::filesystem::path tempPath(const std::string& name) {
    const auto p = std::filesystem::temp_directory_path() /
                   ("occsim-replay-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(p);
    return p;
}

TEST(MaskedReplayCommand, PrintsEveryLayoutAndWritesThePictureAndTheSummary) {
    for (const char* name : {"OcclusionCulling_0.mocrec", "OcclusionCulling_1.mocrec"}) {
        const std::filesystem::path out = tempPath(name);
        const testing::Outcome o =
            testing::shell(std::string(OCCSIM_EXE) + " masked-replay " + (kMoc / name).string() +
                           " --out " + out.string());
        EXPECT_EQ(o.exit_code, 0) << o.output;
        for (const std::string layout : {"8x4", "32x4", "32x8"}) {
            // A row per layout and set of rectangles: "<layout>   8x4 blocks ...".
            const size_t row = o.output.find("\n" + layout + " ");
            ASSERT_NE(row, std::string::npos) << layout << "\n" << o.output;
            const std::string line = o.output.substr(row + 1, o.output.find('\n', row + 1) - row);
            EXPECT_NE(line.find("8x4 blocks"), std::string::npos) << line;
        }
        EXPECT_TRUE(std::filesystem::is_regular_file(out / "depth.png"));
        EXPECT_TRUE(std::filesystem::is_regular_file(out / "summary.json"));
        std::filesystem::remove_all(out);
    }
}

TEST(MaskedReplayCommand, ABrokenFileIsOneLineAndExitTwo) {
    const std::filesystem::path bad = tempPath("bad.mocrec");
    std::ofstream(bad, std::ios::binary) << "not a recorded frame";
    const std::filesystem::path out = tempPath("bad-out");
    const testing::Outcome o = testing::shell(std::string(OCCSIM_EXE) + " masked-replay " +
                                              bad.string() + " --out " + out.string());
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_NE(o.output.find(bad.string() + ": byte 0: "), std::string::npos) << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
    EXPECT_FALSE(std::filesystem::exists(out / "depth.png"));
    std::filesystem::remove(bad);
}

// The case: a valid-looking header asking for 32768 × 32768 pixels (within each side's
// range) ended in "occsim: std::bad_alloc", exit 1; now one line naming the file and the byte.
TEST(MaskedReplayCommand, AFramePastTheMemoryBudgetIsOneLineAndExitTwo) {
    const std::filesystem::path huge = tempPath("huge.mocrec");
    {
        std::ofstream file(huge, std::ios::binary);
        const uint32_t magic = kMocrecMagic, side = 32768;
        const float near_clip = 0.1f;
        const uint8_t end = 0x7F;
        file.write(reinterpret_cast<const char*>(&magic), 4);
        file.write(reinterpret_cast<const char*>(&near_clip), 4);
        file.write(reinterpret_cast<const char*>(&side), 4);
        file.write(reinterpret_cast<const char*>(&side), 4);
        file.write(reinterpret_cast<const char*>(&end), 1);
    }
    const std::filesystem::path out = tempPath("huge-out");
    const testing::Outcome o = testing::shell(std::string(OCCSIM_EXE) + " masked-replay " +
                                              huge.string() + " --out " + out.string());
    EXPECT_EQ(o.exit_code, 2);
    EXPECT_NE(o.output.find(huge.string() + ": byte 8: expected at most 33554432 pixels"),
              std::string::npos)
        << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
    EXPECT_FALSE(std::filesystem::exists(out / "summary.json"));
    std::filesystem::remove(huge);
}

}  // namespace
}  // namespace occsim
