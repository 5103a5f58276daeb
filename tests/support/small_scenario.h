// The small scenario the world and run tests build: 200 low-tessellation teapots in a region in
// front of the camera, a quarter of them bouncing and a tenth orbiting.
#pragma once

#include <cstdint>

#include "sim/scenario/scenario.h"

namespace occsim::testing {

inline Scenario smallScenario(uint64_t seed = 3) {
    Scenario s;
    s.seed = seed;
    TeapotFieldSpec teapots;
    teapots.count = 200;
    teapots.region = {glm::vec3(-20, 0, -50), glm::vec3(20, 5, 0)};
    teapots.tessellation = 2;
    SceneSourceSpec& source = s.sources.emplace_back();
    source.type = SourceType::Teapots;
    source.spec.emplace<TeapotFieldSpec>(teapots);
    MoverSpec bounce;
    bounce.fraction = 0.25;
    bounce.motion = MotionType::Bounce;
    MoverSpec orbit;
    orbit.fraction = 0.1;
    orbit.motion = MotionType::Orbit;
    s.movers = {bounce, orbit};
    s.camera.keyframes.push_back({});
    return s;
}

}  // namespace occsim::testing
