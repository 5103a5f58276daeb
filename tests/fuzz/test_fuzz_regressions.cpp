// Every input a fuzzer found (tests/fuzz/regressions/<target>/) goes through the same function
// its fuzz target calls, in the normal suite and under the sanitizers: each must end in the
// documented error or parse, never crash. The folders also hold a few hand-made hostile inputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_inputs.h"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> inputsOf(const std::string& target) {
    std::vector<fs::path> out;
    const fs::path dir = fs::path(OCCSIM_SOURCE_DIR) / "tests/fuzz/regressions" / target;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.is_regular_file()) out.push_back(e.path());
    }
    return out;
}

std::string bytesOf(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const uint8_t* dataOf(const std::string& s) { return reinterpret_cast<const uint8_t*>(s.data()); }

// Every fuzz target has hand-made hostile inputs at least; each ends in its documented error or
// is accepted, and nothing escapes.
class FuzzRegressions : public ::testing::TestWithParam<occsim::fuzz::FuzzTarget> {};

TEST_P(FuzzRegressions, InputsEndInAcceptanceOrTheReadersOwnError) {
    const auto inputs = inputsOf(std::string(GetParam().name));
    ASSERT_FALSE(inputs.empty()) << "tests/fuzz/regressions/" << GetParam().name << "/ is empty";
    for (const fs::path& file : inputs) {
        SCOPED_TRACE(file.filename().string());
        const std::string bytes = bytesOf(file);
        EXPECT_NO_THROW(GetParam().input(dataOf(bytes), bytes.size()));
    }
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegressions, ::testing::ValuesIn(occsim::fuzz::fuzzTargets()),
                         [](const auto& target) { return std::string(target.param.name); });

// Each target has a valid-* seed it accepts: the targets do reach past the first check of their
// readers (and scripts/fuzz.sh starts every corpus from it).
TEST(FuzzTargets, EachAcceptsItsValidSeed) {
    for (const occsim::fuzz::FuzzTarget& t : occsim::fuzz::fuzzTargets()) {
        bool accepted = false;
        for (const fs::path& file : inputsOf(std::string(t.name))) {
            if (file.filename().string().rfind("valid-", 0) != 0) continue;
            const std::string bytes = bytesOf(file);
            accepted = t.input(dataOf(bytes), bytes.size());
            EXPECT_TRUE(accepted) << t.name << ": " << file.filename();
        }
        EXPECT_TRUE(accepted) << t.name << " has no valid-* seed accepted";
    }
}

}  // namespace
