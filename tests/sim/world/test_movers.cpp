// The movers (sim/world/movers.cpp): bouncers, orbiters, spawners, listed objects, paths, random
// walkers and spinners move as their scenario says, deterministically and within their regions;
// a motion or placement that leaves finite coordinates is named with its object and frame.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sim/world/world.h"
#include "small_scenario.h"

namespace occsim {
namespace {

using testing::smallScenario;

TEST(Movers, BouncersStayInTheirRegionEvenWithHugeSteps) {
    const Scene scene = buildScene(smallScenario());
    WorldState state = initialState(scene);
    for (double dt : {0.01, 0.5, 7.3, 1000.0}) {
        for (int i = 0; i < 50; ++i) stepMovers(scene, state, dt);
        for (const Mover& m : state.movers) {
            if (const auto* b = std::get_if<BounceMotion>(&m.motion)) {
                const glm::dvec3 p = state.poses[m.object].position;
                for (int axis = 0; axis < 3; ++axis) {
                    EXPECT_GE(p[axis], b->region.min[axis] - 1e-9) << "dt " << dt;
                    EXPECT_LE(p[axis], b->region.max[axis] + 1e-9) << "dt " << dt;
                }
            }
        }
    }
}

TEST(Movers, OrbitersKeepTheirRadiusAndSpeedAndBoxesFollowThem) {
    const Scene scene = buildScene(smallScenario());
    WorldState state = initialState(scene);
    const WorldState before = state;
    stepMovers(scene, state, 0.1);
    for (size_t i = 0; i < state.movers.size(); ++i) {
        const Mover& m = state.movers[i];
        const auto* orbit = std::get_if<OrbitMotion>(&m.motion);
        if (!orbit) continue;
        const glm::dvec3 p = state.poses[m.object].position;
        EXPECT_NEAR(glm::length(glm::dvec2(p.x - orbit->center.x, p.z - orbit->center.z)),
                    orbit->radius_m, 1e-9);
        const double travelled = glm::length(p - before.poses[m.object].position);
        EXPECT_NEAR(travelled, std::abs(orbit->angular_speed) * orbit->radius_m * 0.1, 1e-3);
        const Aabb expected =
            worldBox(scene.mesh_bounds[0], state.poses[m.object], scene.culling_origin);
        EXPECT_EQ(state.boxes[m.object].min, expected.min);
    }
}

MoverSpec moverOf(MotionType motion, MoverSelection selection) {
    MoverSpec m;
    m.motion = motion;
    m.selection = selection;
    m.fraction = 0.1;
    m.objects = {0, 5};
    m.spawn.count = 7;
    return m;
}

TEST(Movers, SpawnAddsObjectsWithTheirOwnMeshInsideTheRegion) {
    Scenario s = smallScenario();
    MoverSpec spawn = moverOf(MotionType::Bounce, MoverSelection::Spawn);
    spawn.spawn.shape = SpawnShape::Sphere;
    s.movers = {spawn};
    const Scene scene = buildScene(s);
    EXPECT_EQ(scene.objectCount(), 207u);
    EXPECT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.initial_movers.size(), 7u);
    for (const Mover& m : scene.initial_movers) {
        EXPECT_GE(m.object, 200u);
        const WorldBox& region = std::get<TeapotFieldSpec>(s.sources[0].spec).region;
        EXPECT_TRUE(contains(Aabb{glm::vec3(region.min), glm::vec3(region.max)},
                             glm::vec3(scene.initial_poses[m.object].position)));
    }
}

TEST(Movers, ListedObjectsMoveAndBadIndicesAreErrorsNamingTheMover) {
    Scenario s = smallScenario();
    s.file = "x.json";
    s.movers = {moverOf(MotionType::Spin, MoverSelection::Objects)};
    const Scene scene = buildScene(s);
    ASSERT_EQ(scene.initial_movers.size(), 2u);
    EXPECT_EQ(scene.initial_movers[1].object, 5u);
    s.movers[0].objects = {3, 200};
    try {
        buildScene(s);
        FAIL() << "expected an error";
    } catch (const ScenarioError& e) {
        EXPECT_NE(std::string(e.what()).find("x.json: /movers/0/objects/1"), std::string::npos)
            << e.what();
    }
    s.movers = {moverOf(MotionType::Spin, MoverSelection::Objects),
                moverOf(MotionType::Spin, MoverSelection::Objects)};
    EXPECT_THROW(buildScene(s), ScenarioError) << "an object cannot get two motions";
}

TEST(Movers, PathMoversFollowTheirLoopAtConstantSpeedFacingForward) {
    Scenario s = smallScenario();
    MoverSpec path = moverOf(MotionType::Path, MoverSelection::Spawn);
    path.waypoints = {{0, 0, 0}, {100, 0, 0}, {100, 0, -50}, {0, 0, -50}};
    path.speed_min_mps = path.speed_max_mps = 10.0;
    s.movers = {path};
    const Scene scene = buildScene(s);
    ASSERT_EQ(scene.paths.size(), 1u);
    EXPECT_DOUBLE_EQ(scene.paths[0].total(), 300.0);
    WorldState state = initialState(scene);
    for (int i = 0; i < 100; ++i) {
        const WorldState before = state;
        stepMovers(scene, state, 0.1);
        for (const Mover& m : state.movers) {
            const glm::dvec3 p = state.poses[m.object].position;
            EXPECT_NEAR(p.y, 0.0, 1e-9);
            const bool on_loop = std::abs(p.z) < 1e-6 || std::abs(p.z + 50) < 1e-6 ||
                                 std::abs(p.x) < 1e-6 || std::abs(p.x - 100) < 1e-6;
            EXPECT_TRUE(on_loop) << p.x << " " << p.z;
            // 1 m per step along the loop; across a corner the straight line is shorter.
            const double moved = glm::length(p - before.poses[m.object].position);
            EXPECT_LE(moved, 1.0 + 1e-6);
            EXPECT_GE(moved, 0.7);
        }
    }
}

TEST(Movers, PathWithoutWaypointsOnASourceWithoutLanesIsAnError) {
    Scenario s = smallScenario();
    s.movers = {moverOf(MotionType::Path, MoverSelection::Fraction)};
    EXPECT_THROW(buildScene(s), ScenarioError);
}

TEST(Movers, RandomWalkersStayInTheirRegionAndAreDeterministic) {
    Scenario s = smallScenario();
    MoverSpec walk = moverOf(MotionType::RandomWalk, MoverSelection::Fraction);
    walk.fraction = 0.5;
    walk.has_region = true;
    walk.region = {glm::vec3(-5, 0, -5), glm::vec3(5, 5, 5)};
    s.movers = {walk};
    const Scene scene = buildScene(s);
    WorldState a = initialState(scene), b = initialState(scene);
    for (int i = 0; i < 500; ++i) {
        stepMovers(scene, a, 0.05);
        stepMovers(scene, b, 0.05);
    }
    for (const Mover& m : a.movers) {
        const glm::dvec3 p = a.poses[m.object].position;
        EXPECT_GE(p.x, -5.0 - 1e-9);
        EXPECT_LE(p.x, 5.0 + 1e-9);
        EXPECT_GE(p.z, -5.0 - 1e-9);
        EXPECT_LE(p.z, 5.0 + 1e-9);
        EXPECT_EQ(p, b.poses[m.object].position);
    }
}

TEST(Movers, SpinnersTurnInPlace) {
    Scenario s = smallScenario();
    s.movers = {moverOf(MotionType::Spin, MoverSelection::Objects)};
    const Scene scene = buildScene(s);
    WorldState state = initialState(scene);
    const WorldState before = state;
    stepMovers(scene, state, 0.25);
    for (const Mover& m : state.movers) {
        EXPECT_EQ(state.poses[m.object].position, before.poses[m.object].position);
        EXPECT_GT(
            std::abs(glm::dot(state.poses[m.object].rotation, before.poses[m.object].rotation) -
                     1.0f),
            1e-4f);
    }
}
// A motion that leaves finite float coordinates (here an orbit far larger than a float can hold)
// stops the run with an error naming the object and the frame, instead of letting an infinite
// box into the tree.
TEST(Movers, AMotionThatLeavesFiniteCoordinatesStopsTheRunNamingObjectAndFrame) {
    Scenario s = smallScenario();
    s.movers.resize(1);
    s.movers[0].motion = MotionType::Orbit;
    s.movers[0].fraction = 0.05;
    s.movers[0].radius_min_m = s.movers[0].radius_max_m = 1e39;
    s.movers[0].speed_min_mps = s.movers[0].speed_max_mps = 1e300;
    const Scene scene = buildScene(s);
    WorldState state = initialState(scene);
    EXPECT_NO_THROW(requireFiniteBoxes(state, 0));
    const uint32_t first_mover_object = state.movers.front().object;
    try {
        for (uint32_t frame = 1; frame < 100; ++frame) {
            stepMovers(scene, state, 1.0 / 30.0);
            requireFiniteBoxes(state, frame);
        }
        ADD_FAILURE() << "expected a MotionError";
    } catch (const MotionError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind("frame 1: object ", 0), 0u) << message;
        EXPECT_NE(message.find("object " + std::to_string(first_mover_object)), std::string::npos)
            << message;
        EXPECT_NE(message.find("left finite float coordinates"), std::string::npos) << message;
    }
}

// A glTF scale animation to 3e38 overflows a box at the origin: the message names the scale, not
// only a position that is fine.
TEST(Movers, AnOverflowingScaleIsNamedInTheMessage) {
    WorldState state;
    state.poses.resize(1);
    state.poses[0].linear = glm::mat3(3e38f);
    state.boxes = {Aabb{{0, 0, 0}, {std::numeric_limits<float>::infinity(), 1, 1}}};
    state.moved = {0};
    try {
        requireFiniteBoxes(state, 2);
        ADD_FAILURE() << "expected a MotionError";
    } catch (const MotionError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("its position is (0, 0, 0), its scale 3e+38"), std::string::npos)
            << message;
    }
}

TEST(Movers, PlacementsOutsideFiniteCoordinatesAreNamedToo) {
    WorldState state;
    state.poses.resize(3);
    state.boxes = {Aabb{{0, 0, 0}, {1, 1, 1}}, Aabb{{0, 0, 0}, {1, 1, 1}},
                   Aabb{{0, 0, 0}, {std::numeric_limits<float>::infinity(), 1, 1}}};
    try {
        requireFiniteBoxes(state, 0);
        ADD_FAILURE() << "expected a MotionError";
    } catch (const MotionError& e) {
        EXPECT_NE(std::string(e.what()).find("frame 0: object 2 as placed"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace occsim
