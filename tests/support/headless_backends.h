// The headless backends the tests that touch OpenGL run on: EGL always, OSMesa where the build
// has it (OCCSIM_WITH_OSMESA). Use with INSTANTIATE_TEST_SUITE_P(..., testedBackends(),
// backendTestName).
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "render/headless_context.h"

namespace occsim::testing {

inline std::vector<Backend> testedBackends() {
    std::vector<Backend> backends = {Backend::Egl};
    if (osmesaAvailable()) backends.push_back(Backend::OsMesa);
    return backends;
}

inline std::string backendTestName(const ::testing::TestParamInfo<Backend>& info) {
    return backendName(info.param);
}

}  // namespace occsim::testing
