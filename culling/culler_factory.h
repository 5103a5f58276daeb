// Cullers by name, with their options. Names: vfc, stop-and-wait, statistical, chc, chc++, async,
// ideal.
#pragma once

#include "culling/async_culler.h"
#include "culling/chc_culler.h"
#include "culling/chcpp_culler.h"
#include "culling/culler.h"
#include "culling/statistical_culler.h"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace occsim {

struct CullerOptions {
    StatisticalOptions statistical;
    ChcOptions chc;
    ChcppOptions chcpp;
    AsyncOptions async;
};

const std::vector<std::string>& cullerNames();

// nullptr when the name is unknown.
std::unique_ptr<Culler> makeCuller(std::string_view name, const CullerOptions& options);

}  // namespace occsim
