// Cullers by name, with their options. Names: vfc, stop-and-wait, statistical, ideal.
#pragma once

#include "culling/culler.h"
#include "culling/statistical_culler.h"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace occsim {

struct CullerOptions {
    StatisticalOptions statistical;
};

const std::vector<std::string>& cullerNames();

// nullptr when the name is unknown.
std::unique_ptr<Culler> makeCuller(std::string_view name, const CullerOptions& options);

}  // namespace occsim
