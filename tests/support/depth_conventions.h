// Both depth conventions (render/gl_renderer.h), for a suite run in each: the values and the
// name each test gets.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "render/gl_renderer.h"

namespace occsim {

inline auto bothDepthConventions() {
    return ::testing::Values(DepthConvention::ReverseFloat, DepthConvention::Conventional24);
}
inline std::string depthConventionName(const ::testing::TestParamInfo<DepthConvention>& param) {
    return param.param == DepthConvention::ReverseFloat ? "ReverseFloat" : "Conventional24";
}

}  // namespace occsim
