// Posing the moving copies of glTF models (sim/world/model_copies.h): an animation's own time from
// the simulation time in each play mode. Copies posed in a world (tight boxes, per-copy phases,
// whole-copy movers, spawned models): test_gltf_animation.cpp.
#include <gtest/gtest.h>

#include "sim/world/model_copies.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

TEST(AnimationPlayback, LoopClampAndPingPongOverTheAnimationsOwnDuration) {
    SceneModel m;
    EXPECT_DOUBLE_EQ(animationTime(m, 2.0, 0.0, 0.5), 0.5);
    EXPECT_DOUBLE_EQ(animationTime(m, 2.0, 0.0, 2.5), 0.5);  // loops
    EXPECT_DOUBLE_EQ(animationTime(m, 2.0, 0.0, 2.0), 2.0);  // the end shows the last key
    EXPECT_DOUBLE_EQ(animationTime(m, 2.0, 0.0, 0.0), 0.0);
    m.mode = AnimationMode::Clamp;
    EXPECT_DOUBLE_EQ(animationTime(m, 2.0, 0.0, 5.0), 2.0);
    m.mode = AnimationMode::PingPong;
    EXPECT_DOUBLE_EQ(animationTime(m, 2.0, 0.0, 2.5), 1.5);
    EXPECT_DOUBLE_EQ(animationTime(m, 2.0, 0.0, 4.5), 0.5);
    m.mode = AnimationMode::Loop;
    m.speed = 2.0;
    m.time_offset_s = 0.5;
    EXPECT_DOUBLE_EQ(animationTime(m, 2.0, 0.25, 0.5), 1.75);  // 0.5 + 0.25 + 2 * 0.5
}

}  // namespace
}  // namespace occsim
