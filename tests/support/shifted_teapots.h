// The small teapot scenario (scenarios/small/teapots-small.json) with every position it holds
// moved, for the tests that run a scene far from the world origin: its camera keyframes and its
// sources' regions, its expectations left out.
#pragma once

#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "sim/scenario/scenario.h"

namespace occsim::testing {

inline const std::filesystem::path kSmallTeapots =
    std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios/small/teapots-small.json";

inline Scenario shiftedTeapots(const glm::dvec3& by) {
    nlohmann::json s = nlohmann::json::parse(std::ifstream(kSmallTeapots));
    auto shift = [&by](nlohmann::json& p) {
        for (int i = 0; i < 3; ++i) p[i] = p[i].get<double>() + by[i];
    };
    for (nlohmann::json& key : s["camera"]["keyframes"]) {
        shift(key["position"]);
        shift(key["target"]);
    }
    for (nlohmann::json& source : s["scene"]["sources"]) {
        shift(source["region"]["min"]);
        shift(source["region"]["max"]);
    }
    s.erase("expect");
    return parseScenarioText(s.dump(), kSmallTeapots);
}

}  // namespace occsim::testing
