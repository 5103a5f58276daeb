// Frames of a culler on the scripted query device, and the conservativeness check the CHC, CHC++
// and per-object culler tests share (test_chc_culler.cpp, test_chcpp_culler.cpp,
// test_async_culler.cpp).
#pragma once

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "bsp_tree_checks.h"  // sameBox
#include "culling_fixtures.h"
#include "occsim/culling/testing/scripted_query_device.h"

namespace occsim::testing {

// What a frame did, read from the scripted device's log.
struct FrameLog {
    std::vector<uint32_t> drawn;
    uint64_t queries = 0;
    uint64_t waited = 0;
};

inline FrameLog runFrame(Culler& culler, const BspTree& tree, ScriptedQueryDevice& device,
                         const std::vector<Aabb>& boxes, const std::vector<uint8_t>& visible,
                         const CullView& view, uint64_t frame) {
    device.setVisibility(visible, boxes);
    device.clearLog();
    device.resetCounters();
    culler.cullAndRender(tree, makeFrame(view, frame, static_cast<double>(frame) / 30.0), device);
    return {device.drawnObjects(), device.counters().queries_issued,
            device.counters().results_waited};
}

// Every object in the frustum that the script says is visible is drawn, nothing outside the
// frustum is, and nothing twice.
inline void expectConservative(const FrameLog& log, const std::vector<Aabb>& boxes,
                               const std::vector<uint8_t>& visible, const CullView& view,
                               const std::string& what) {
    const std::set<uint32_t> frustum = inFrustum(boxes, view.frustum);
    std::set<uint32_t> drawn;
    for (uint32_t o : log.drawn) {
        EXPECT_TRUE(drawn.insert(o).second) << what << ": object " << o << " drawn twice";
        EXPECT_TRUE(frustum.count(o)) << what << ": object " << o << " drawn outside the frustum";
    }
    for (uint32_t o : frustum) {
        if (visible[o]) {
            EXPECT_TRUE(drawn.count(o)) << what << ": visible object " << o << " missed";
        }
    }
}

}  // namespace occsim::testing
