// What `occsim info` prints: objects, triangles, movers, the BSP tree (nodes, depth, where objects
// live) and the scene bounds. Builds the scene and the tree; renders nothing.
#pragma once

#include <string>
#include <vector>

#include "sim/scenario/scenario.h"

namespace occsim {

// The scene's own warnings (e.g. glTF parts skipped) are appended to `warnings`.
std::string describeScenario(const Scenario& scenario, std::vector<std::string>& warnings);

}  // namespace occsim
