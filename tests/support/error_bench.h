// The small scenarios benchmarked with the error measured, as the tests of the error metric use
// them (ground truth, the simulation, the error picture): a bench of named cullers in
// deterministic latency, a run's summary by name, the conservative cullers, and the check that a
// run drew every visible pixel.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"
#include "sim/run/runner.h"
#include "sim/scenario/scenario.h"

namespace occsim::testing {

inline const std::filesystem::path kScenarios =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/small";
inline const std::filesystem::path kSharedFaces = kScenarios / "shared-faces-small.json";
inline const std::filesystem::path kDeepDepth = kScenarios / "deep-depth-small.json";
inline const std::filesystem::path kTeapots = kScenarios / "teapots-small.json";

// The scenario `file` with `algorithms`, the error measured, in deterministic latency (8 frames);
// `frames` > 0 cuts the run.
inline BenchResult errorBench(const std::filesystem::path& file,
                              const std::vector<std::string>& algorithms, uint32_t frames = 0,
                              BenchOptions options = {}) {
    for (const std::string& n : algorithms) options.algorithms.push_back(findCuller(n));
    options.measure_error = true;
    options.latency = {true, 8};
    if (frames > 0) options.frames = frames;
    return runBenchmark(parseScenarioFile(file), options);
}

// A bench of these cullers with the error measured, in deterministic latency (8 commands), cut
// to `frames`: what the tests of a scenario built in code run.
inline BenchOptions errorBenchOf(std::initializer_list<const char*> cullers, uint32_t frames) {
    BenchOptions options;
    for (const char* name : cullers) options.algorithms.push_back(findCuller(name));
    options.measure_error = true;
    options.latency = {true, 8};
    options.frames = frames;
    return options;
}

inline const RunSummary& summaryOf(const BenchResult& result, const std::string& name) {
    for (const RunRecord& r : result.runs) {
        if (r.summary.label == name) return r.summary;
    }
    throw std::runtime_error("no run " + name);
}

// The registry's conservative cullers, by name.
inline std::vector<std::string> conservativeAlgorithms() {
    std::vector<std::string> out;
    for (const std::string& name : cullerNames()) {
        if (findCuller(name)->conservative) out.push_back(name);
    }
    return out;
}

// No error pixel and no missed object on any frame of any run.
inline void expectNoErrorAndNoMiss(const BenchResult& result) {
    for (const RunRecord& run : result.runs) {
        for (const FrameStats& f : run.frames) {
            EXPECT_EQ(f.error_pixels, 0) << run.summary.label << " frame " << f.frame;
            EXPECT_EQ(f.missed_objects, 0) << run.summary.label << " frame " << f.frame;
            EXPECT_GE(f.tie_pixels, 0);
            EXPECT_GT(f.visible_objects, 0);
        }
    }
}

}  // namespace occsim::testing
