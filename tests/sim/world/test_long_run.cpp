// The long run (ctest label `stress` only; docs/stability.md): 10^6 frames of simulation and
// reinsertion, no rendering, with thousands of movers fast enough to cross several cells a frame.
// Every 10^4 frames the tree is checked from scratch; the object count must be conserved and the
// resident memory flat. It prints the figures docs/stability.md quotes.
// OCCSIM_LONG_RUN_FRAMES overrides the frame count (for trying it out).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "bsp_tree_checks.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

// A /proc/self/status figure in kB (VmRSS: resident now, VmHWM: the peak so far).
long statusKb(const std::string& key) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind(key + ":", 0) == 0)
            return std::strtol(line.c_str() + key.size() + 1, nullptr, 10);
    }
    return -1;
}

Scenario soakScenario() {
    Scenario s;
    s.seed = 99;
    s.dt_s = 1.0 / 30.0;
    TeapotFieldSpec teapots;
    teapots.count = 3000;
    teapots.region = {glm::vec3(-60, 0, -60), glm::vec3(60, 10, 60)};
    teapots.size_min_m = 0.5;
    teapots.size_max_m = 2.0;
    teapots.tessellation = 1;
    SceneSourceSpec& source = s.sources.emplace_back();
    source.type = SourceType::Teapots;
    source.spec.emplace<TeapotFieldSpec>(teapots);
    MoverSpec fast;  // 2,000 bouncers at 60 to 150 m/s: 2 to 5 m per frame, beyond a leaf's cell
    fast.fraction = 2.0 / 3.0;
    fast.motion = MotionType::Bounce;
    fast.speed_min_mps = 60;
    fast.speed_max_mps = 150;
    fast.has_region = true;
    fast.region = {glm::vec3(-80, -5, -80), glm::vec3(80, 15, 80)};  // beyond the built root cell
    s.movers = {fast};
    s.camera.keyframes.push_back({});
    return s;
}

TEST(LongRun, AMillionFramesOfFastMoversLoseNoObjectKeepTheTreeValidAndTheMemoryFlat) {
    const char* override_frames = std::getenv("OCCSIM_LONG_RUN_FRAMES");
    const uint64_t frames = override_frames ? std::strtoull(override_frames, nullptr, 10) : 1000000;
    constexpr uint64_t kCheckEvery = 10000;
    const Scenario scenario = soakScenario();
    const Scene scene = buildScene(scenario);
    WorldState state = initialState(scene);
    BspTree tree;
    BspBuildOptions bsp;
    bsp.split_rule = BspSplitRule::Sah;
    tree.build(state.boxes, bsp);
    ASSERT_EQ(scene.initial_movers.size(), 2000u);

    long rss_start_kb = -1;
    const auto start = std::chrono::steady_clock::now();
    for (uint64_t frame = 1; frame <= frames; ++frame) {
        stepMovers(scene, state, scenario.dt_s);
        requireFiniteBoxes(state, static_cast<uint32_t>(frame));
        for (const Mover& mover : state.movers)
            tree.reinsert(mover.object, state.boxes[mover.object]);
        tree.refitDirtyBounds();
        if (frame % kCheckEvery == 0 || frame == frames) {
            ASSERT_EQ(tree.objectCount(), scene.objectCount());
            uint64_t placed = 0;
            for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
                if (tree.isLive(n)) placed += tree.node(n).object_count;
            }
            ASSERT_EQ(placed, scene.objectCount()) << "frame " << frame;
            testing::expectTreeInvariants(tree);
            if (::testing::Test::HasFailure())
                FAIL() << "tree invariants broken at frame " << frame;
            // Memory is measured from the first check on, once every structure has its size.
            if (rss_start_kb < 0) rss_start_kb = statusKb("VmRSS");
        }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const long rss_end_kb = statusKb("VmRSS");
    const long peak_kb = statusKb("VmHWM");
    std::printf(
        "long run: %llu frames, %zu movers, %u objects: %.1f s, %.3f ms per frame; "
        "resident %ld kB after %llu frames, %ld kB at the end, peak %ld kB; %u live nodes\n",
        static_cast<unsigned long long>(frames), state.movers.size(), scene.objectCount(), seconds,
        1e3 * seconds / static_cast<double>(frames), rss_start_kb,
        static_cast<unsigned long long>(std::min<uint64_t>(kCheckEvery, frames)), rss_end_kb,
        peak_kb, tree.liveNodeCount());
    EXPECT_LE(rss_end_kb, rss_start_kb + rss_start_kb / 20 + 1024) << "memory must stay flat";
}

}  // namespace
}  // namespace occsim
