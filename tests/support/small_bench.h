// The small teapot scenario benchmarked headless, as the run and output tests use it: its path, a
// fresh folder of this process, the registry's rows of some cullers, and a bench of them.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

namespace occsim::testing {

inline const std::filesystem::path kSmall =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json";

inline std::filesystem::path freshDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("occsim-test-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::remove_all(dir);
    return dir;
}

inline std::vector<const CullerRow*> traitsOf(const std::vector<std::string>& names) {
    std::vector<const CullerRow*> out;
    for (const std::string& n : names) out.push_back(findCuller(n));
    return out;
}

inline BenchResult benchSmall(bool error, LatencyMode latency,
                              const std::vector<std::string>& algorithms = cullerNames()) {
    BenchOptions options;
    options.algorithms = traitsOf(algorithms);
    options.measure_error = error;
    options.latency = latency;
    return runBenchmark(parseScenarioFile(kSmall), options);
}

}  // namespace occsim::testing
