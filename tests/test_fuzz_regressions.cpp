// Every input a fuzzer found (tests/fuzz/regressions/<target>/) goes through the same function
// its fuzz target calls, in the normal suite and under the sanitizers: each must end in the
// documented error or parse, never crash. The folders also hold a few hand-made hostile inputs.
#include "fuzz_inputs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

TEST(FuzzRegressions, ScenarioInputsEndInAParseOrAScenarioError) {
    const auto inputs = inputsOf("scenario");
    ASSERT_FALSE(inputs.empty());
    for (const fs::path& file : inputs) {
        SCOPED_TRACE(file.filename().string());
        const std::string bytes = bytesOf(file);
        EXPECT_NO_THROW(occsim::fuzz::scenarioInput(dataOf(bytes), bytes.size()));
    }
}

TEST(FuzzRegressions, GltfInputsEndInALoadOrAGltfError) {
    const auto inputs = inputsOf("gltf");
    ASSERT_FALSE(inputs.empty());
    for (const fs::path& file : inputs) {
        SCOPED_TRACE(file.filename().string());
        const std::string bytes = bytesOf(file);
        EXPECT_NO_THROW(occsim::fuzz::gltfInput(dataOf(bytes), bytes.size()));
    }
}

}  // namespace
