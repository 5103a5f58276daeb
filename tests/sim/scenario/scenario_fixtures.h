// What the scenario parser's test files share: the smallest scenario, and the checks that a bad
// one fails with the file, the JSON pointer and the words expected.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "culling/cullers/statistical_culler.h"
#include "occsim/culling/registry/registry.h"
#include "sim/scenario/scenario.h"

namespace occsim::fixtures {

using nlohmann::json;

inline const char* const kFile = "scenarios/bad-input.json";

// The smallest scenario the format accepts.
inline json minimalScenario() {
    return json::parse(R"({
        "format_version": 1,
        "camera": {"keyframes": [{"time": 0, "position": [0, 2, 10], "target": [0, 2, 0]}]},
        "scene": {"sources": [{"type": "teapots"}]}
    })");
}

// Parses `text` and returns the error message; fails the test when parsing succeeds.
inline std::string errorForText(const std::string& text) {
    try {
        parseScenarioText(text, kFile);
    } catch (const ScenarioError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a ScenarioError for:\n" << text;
    return {};
}

inline std::string errorFor(const json& scenario) { return errorForText(scenario.dump(2)); }

// A culler's option values as the scenario gave them (or their defaults).
inline OptionValues optionsOf(const Scenario& s, const char* culler) {
    return s.culler.of(*findCuller(culler));
}

inline StatisticalOptions statisticalOf(const Scenario& s, const char* culler = "statistical") {
    return statisticalOptionTable().read(optionsOf(s, culler));
}

// The message must be "<file>: <pointer>: ..." (just "<file>: ..." for errors about the whole
// file, pointer "") and contain `fragment`.
inline void expectError(const std::string& message, const std::string& pointer,
                        const std::string& fragment) {
    const std::string prefix = std::string(kFile) + ": " + (pointer.empty() ? "" : pointer + ": ");
    EXPECT_EQ(message.rfind(prefix, 0), 0u)
        << "message: " << message << "\nexpected prefix: " << prefix;
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "message: " << message << "\nexpected to contain: " << fragment;
}

inline void expectError(const json& scenario, const std::string& pointer,
                        const std::string& fragment) {
    expectError(errorFor(scenario), pointer, fragment);
}

}  // namespace occsim::fixtures
