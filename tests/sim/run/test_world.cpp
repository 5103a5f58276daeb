// Scene building, movers and the camera path: deterministic, bounded, smooth.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gltf_builder.h"
#include "sim/run/frame_stats.h"
#include "sim/run/shared_world.h"
#include "sim/scenario/scenario.h"
#include "sim/world/camera_path.h"
#include "sim/world/seed_effect.h"
#include "sim/world/world.h"

namespace occsim {
namespace {

Scenario smallScenario(uint64_t seed = 3) {
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

TEST(Scene, TeapotFieldIsDeterministicPerSeedAndDiffersAcrossSeeds) {
    const Scene a = buildScene(smallScenario(3));
    const Scene b = buildScene(smallScenario(3));
    const Scene c = buildScene(smallScenario(4));
    ASSERT_EQ(a.objectCount(), 200u);
    for (uint32_t o = 0; o < a.objectCount(); ++o) {
        EXPECT_EQ(a.initial_poses[o].position, b.initial_poses[o].position);
        EXPECT_EQ(a.initial_poses[o].linear, b.initial_poses[o].linear);
    }
    EXPECT_NE(a.initial_poses[0].position, c.initial_poses[0].position);
    ASSERT_EQ(a.initial_movers.size(), b.initial_movers.size());
    for (size_t m = 0; m < a.initial_movers.size(); ++m) {
        EXPECT_EQ(a.initial_movers[m].object, b.initial_movers[m].object);
    }
}

// What a held-out seed changes (occtune says it): everything in a generated field with seeded
// movers; nothing in a glTF level placed as its file lays it; only the phases where its
// animations start at a seeded phase.
TEST(SeedEffect, SaysWhatAnotherSeedChangesInTheScene) {
    const SeedEffect field =
        seedEffect(buildScene(smallScenario(3)), buildScene(smallScenario(4)), 1.0 / 30, 10);
    EXPECT_TRUE(field.layout);
    EXPECT_TRUE(field.which_move);
    EXPECT_TRUE(field.motion);
    EXPECT_FALSE(field.phases);
    EXPECT_EQ(field.text(),
              "the layout of the scene, which objects move and the movers' starts "
              "and motions");
    EXPECT_FALSE(
        seedEffect(buildScene(smallScenario(3)), buildScene(smallScenario(3)), 1.0 / 30, 10).any());

    auto gltfScenario = [](uint64_t seed, const std::string& source) {
        const std::string text = R"({"format_version": 1, "name": "level", "seed": )" +
                                 std::to_string(seed) + R"(, "frames": 10,
            "camera": {"keyframes": [{"time": 0, "position": [0, 2, 10], "target": [0, 0, 0]}]},
            "scene": {"sources": [)" +
                                 source + "]}}";
        return parseScenarioText(
            text, std::filesystem::path(OCCSIM_SOURCE_DIR) / "scenarios" / "level.json");
    };
    const std::string house =
        R"({"type": "gltf", "path": "assets/FZK-Haus/AC14-FZK-Haus.glb",
            "replicate": {"mode": "grid", "count_x": 2, "count_z": 1}})";
    const SeedEffect level = seedEffect(buildScene(gltfScenario(1, house)),
                                        buildScene(gltfScenario(2, house)), 1.0 / 30, 10);
    EXPECT_FALSE(level.any());
    EXPECT_EQ(level.text(), "nothing");
    const std::string boxes =
        R"({"type": "gltf", "path": "assets/BoxAnimated/BoxAnimated.gltf",
            "replicate": {"mode": "grid", "count_x": 3, "count_z": 1, "spacing": 4},
            "animation": {"play": "all", "random_phase": true}})";
    const SeedEffect animated = seedEffect(buildScene(gltfScenario(1, boxes)),
                                           buildScene(gltfScenario(2, boxes)), 1.0 / 30, 10);
    EXPECT_EQ(animated.text(), "the phases of the glTF animations");
}

TEST(Scene, PlacesTeapotsInsideTheRegionWithSizesInRange) {
    const Scenario s = smallScenario();
    const Scene scene = buildScene(s);
    const auto& spec = std::get<TeapotFieldSpec>(s.sources[0].spec);
    for (const ObjectPose& p : scene.initial_poses) {
        EXPECT_TRUE(contains(Aabb{glm::vec3(spec.region.min), glm::vec3(spec.region.max)},
                             glm::vec3(p.position)));
        const float scale = glm::length(p.linear[1]);  // the y column: height scale
        EXPECT_GE(scale, spec.size_min_m - 1e-5);
        EXPECT_LE(scale, spec.size_max_m + 1e-5);
    }
    EXPECT_EQ(scene.triangle_count, 200u * scene.meshes[0].triangleCount());
}

TEST(Scene, MoverFractionsPickDistinctObjectsAndNeverTwoMotionsForOne) {
    const Scene scene = buildScene(smallScenario());
    EXPECT_EQ(scene.initial_movers.size(), 50u + 20u);  // 25% and 10% of 200
    std::vector<int> seen(scene.objectCount());
    for (const Mover& m : scene.initial_movers) ++seen[m.object];
    for (int count : seen) EXPECT_LE(count, 1) << "an object carries one motion at most";
}

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

TEST(CameraPath, PassesThroughKeyframesAndHoldsAtTheEnds) {
    CameraSpec camera;
    camera.keyframes = {{0.0, {0, 0, 0}, {0, 0, -1}},
                        {1.0, {10, 0, 0}, {10, 0, -1}},
                        {3.0, {10, 0, -20}, {0, 0, -20}}};
    EXPECT_EQ(sampleCameraPath(camera, -1.0).position, glm::dvec3(0, 0, 0));
    EXPECT_EQ(sampleCameraPath(camera, 1.0).position, glm::dvec3(10, 0, 0));
    EXPECT_EQ(sampleCameraPath(camera, 3.0).position, glm::dvec3(10, 0, -20));
    EXPECT_EQ(sampleCameraPath(camera, 99.0).position, glm::dvec3(10, 0, -20));
    const glm::dvec3 mid = sampleCameraPath(camera, 2.0).position;
    EXPECT_GT(mid.x, 5.0);
    EXPECT_LT(mid.z, -5.0);
}

TEST(CameraPath, IsContinuousAcrossKeyframes) {
    CameraSpec camera;
    camera.keyframes = {{0.0, {0, 0, 0}, {0, 0, -1}},
                        {1.0, {10, 0, 0}, {10, 0, -1}},
                        {2.0, {10, 5, -10}, {0, 0, -20}},
                        {4.0, {0, 0, -30}, {0, 0, -40}}};
    for (double t = 0.0; t < 4.0; t += 0.001) {
        const double step = glm::length(sampleCameraPath(camera, t + 0.001).position -
                                        sampleCameraPath(camera, t).position);
        EXPECT_LT(step, 0.05) << "jump at t = " << t;
    }
}

TEST(CameraPath, LoopsWhenAsked) {
    CameraSpec camera;
    camera.loop = true;
    camera.keyframes = {
        {0.0, {0, 0, 0}, {0, 0, -1}}, {1.0, {10, 0, 0}, {10, 0, -1}}, {2.0, {0, 0, 0}, {0, 0, -1}}};
    const glm::dvec3 a = sampleCameraPath(camera, 0.7).position;
    const glm::dvec3 b = sampleCameraPath(camera, 2.7).position;
    EXPECT_NEAR(glm::length(a - b), 0.0, 1e-9);
}

TEST(Distribution, MeanMedianAndNearestRankP95) {
    std::vector<double> v;
    for (int i = 1; i <= 100; ++i) v.push_back(i);
    const Distribution d = distributionOf(v);
    EXPECT_DOUBLE_EQ(d.mean, 50.5);
    EXPECT_DOUBLE_EQ(d.median, 50.5);
    EXPECT_DOUBLE_EQ(d.p95, 95.0);
    EXPECT_DOUBLE_EQ(d.min, 1.0);
    EXPECT_DOUBLE_EQ(d.max, 100.0);
    EXPECT_DOUBLE_EQ(distributionOf({3.0}).p95, 3.0);
}

TEST(Pareto, KeepsExactlyThePointsNoOtherPointBeatsInTimeAndError) {
    // (time, error): b dominates d; c and e tie in time, e has less error; a is fastest.
    const std::vector<double> time = {1.0, 2.0, 3.0, 2.5, 3.0, 5.0};
    const std::vector<double> error = {9.0, 4.0, 3.0, 4.0, 1.0, 0.0};
    const std::vector<bool> front = paretoFront(time, error);
    EXPECT_EQ(front, (std::vector<bool>{true, true, false, false, true, true}));
    EXPECT_EQ(paretoFront({1.0, 1.0}, {2.0, 2.0}), (std::vector<bool>{true, true}))
        << "identical points do not dominate each other";
}

TEST(Popping, CountsConsecutiveMissingFramesPerObject) {
    PoppingCounter counter;
    // Object 0 misses frames 1-3, object 1 misses frame 0 and frames 2, object 2 misses 4-5 (open).
    const std::vector<std::vector<uint8_t>> frames = {{0, 1, 0}, {1, 0, 0}, {1, 1, 0},
                                                      {1, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    for (const auto& f : frames) counter.addFrame(f);
    std::vector<uint32_t> runs = counter.runs();
    std::sort(runs.begin(), runs.end());
    EXPECT_EQ(runs, (std::vector<uint32_t>{1, 1, 2, 3}));
    RunSummary s;
    addPopping(s, runs);
    EXPECT_EQ(s.popping_events, 4u);
    EXPECT_EQ(s.popping_max_frames, 3u);
    EXPECT_DOUBLE_EQ(s.popping_mean_frames, 7.0 / 4.0);
}

TEST(Summary, ErrorPerFrameMeanAndP99) {
    std::vector<FrameStats> frames(100);
    for (uint32_t i = 0; i < 100; ++i) {
        frames[i].frame = i;
        frames[i].error_pixels = i;  // 0..99
        frames[i].missed_objects = 0;
    }
    const RunSummary s = summarize("x", frames, 0);
    EXPECT_DOUBLE_EQ(s.error_pixels_mean, 49.5);
    EXPECT_DOUBLE_EQ(s.error_pixels_p99, 98.0);
    EXPECT_EQ(s.error_pixels_worst, 99);
}

TEST(Summary, RepetitionsGiveMediansAndTheSpreadOfTheMean) {
    RunSummary a, b, c;
    a.frame_ms.mean = 10, b.frame_ms.mean = 30, c.frame_ms.mean = 12;
    a.queries_mean = 5, b.queries_mean = 5, c.queries_mean = 8;
    const RunSummary m = aggregateRepetitions({a, b, c});
    EXPECT_EQ(m.repetitions, 3u);
    EXPECT_DOUBLE_EQ(m.frame_ms.mean, 12.0);
    EXPECT_DOUBLE_EQ(m.frame_ms_mean_min, 10.0);
    EXPECT_DOUBLE_EQ(m.frame_ms_mean_max, 30.0);
    EXPECT_DOUBLE_EQ(m.queries_mean, 5.0);
}

// Issue 40's case: async with (0 px, 0 missed), (0, 0) and (2 px, 1 missed) over three
// repetitions. A median would report it exact; the counts are summed, the worst kept.
TEST(Summary, RepetitionsSumErrorCountsInsteadOfTakingTheirMedian) {
    RunSummary clean, miss;
    clean.frames = miss.frames = 120;
    clean.frame_ms.mean = 10, miss.frame_ms.mean = 11;
    miss.error_pixels_total = 2;
    miss.missed_objects_total = 1;
    miss.frames_with_error = 1;
    miss.error_pixels_worst = 2;
    miss.error_worst_frame = 57;
    miss.error_pixels_mean = 2.0 / 120.0;
    miss.error_pixels_p99 = 0;
    miss.tie_pixels_total = 4;
    miss.popping_events = 1;
    miss.popping_mean_frames = 1;
    miss.popping_max_frames = 1;
    const RunSummary m = aggregateRepetitions({clean, clean, miss});
    EXPECT_EQ(m.error_pixels_total, 2);
    EXPECT_EQ(m.missed_objects_total, 1);
    EXPECT_EQ(m.frames_with_error, 1u);
    EXPECT_EQ(m.error_pixels_worst, 2);
    EXPECT_EQ(m.error_worst_frame, 57u);
    EXPECT_EQ(m.tie_pixels_total, 4);
    EXPECT_EQ(m.popping_events, 1u);
    EXPECT_GT(m.error_pixels_mean, 0.0) << "a miss in one repetition keeps the mean above zero";
    EXPECT_DOUBLE_EQ(m.error_pixels_mean, 2.0 / 360.0);
    EXPECT_DOUBLE_EQ(m.frame_ms.mean, 10.0) << "times keep their median";
    // The same three ways round: a sum, whatever the order.
    EXPECT_EQ(aggregateRepetitions({miss, clean, miss}).missed_objects_total, 2);
}

// A Pareto mark decided by a difference below the run-to-run noise is a tie: with repetitions,
// two times whose ranges overlap are not told apart.
TEST(Summary, TheParetoFrontTiesTimesWhoseSpreadsOverlap) {
    // a: 10.0 ms [9.5-10.5], 0 error; b: 10.2 ms [9.8-10.6], 0 error: neither is faster.
    EXPECT_EQ(paretoFront({9.5, 9.8}, {10.5, 10.6}, {0.0, 0.0}), (std::vector<bool>{true, true}));
    // Apart beyond the spread, the slower one drops off.
    EXPECT_EQ(paretoFront({9.5, 11.0}, {10.5, 11.6}, {0.0, 0.0}), (std::vector<bool>{true, false}));
    // Tied on time, the one with less error dominates.
    EXPECT_EQ(paretoFront({9.5, 9.8}, {10.5, 10.6}, {0.1, 0.0}), (std::vector<bool>{false, true}));
    // One repetition: the means decide, as before.
    EXPECT_EQ(paretoFront({10.0, 10.2}, {0.0, 0.0}), (std::vector<bool>{true, false}));
}

TEST(Summary, TimingSkipsWarmupFramesButErrorCountsEveryFrame) {
    std::vector<FrameStats> frames(10);
    for (uint32_t i = 0; i < 10; ++i) {
        frames[i].frame = i;
        frames[i].frame_ms = i < 3 ? 1000.0 : 10.0;
        frames[i].error_pixels = i == 1 ? 7 : 0;
        frames[i].missed_objects = i == 1 ? 1 : 0;
    }
    const RunSummary s = summarize("x", frames, 3);
    EXPECT_EQ(s.timed_frames, 7u);
    EXPECT_DOUBLE_EQ(s.frame_ms.mean, 10.0);
    EXPECT_EQ(s.error_pixels_total, 7);
    EXPECT_EQ(s.error_worst_frame, 1u);
    EXPECT_EQ(s.frames_with_error, 1u);
}

}  // namespace
}  // namespace occsim

namespace occsim {
namespace {

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

namespace occsim {
namespace {

// Boxes are relative to the scene's culling origin and rounded outward: far from the world origin
// they still contain the object (a float box rounded to nearest could cut a few centimetres off).
TEST(WorldBoxes, AreRelativeToTheCullingOriginAndRoundedOutward) {
    const Aabb unit{{-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}};
    ObjectPose pose;
    pose.position = {1e6 + 0.01, 3.3, -2e6 - 0.07};
    const glm::dvec3 origin(1e6, 0, -2e6);
    const Aabb near = worldBox(unit, pose, origin);
    EXPECT_NEAR(near.min.x, 0.01 - 0.5, 1e-6);
    EXPECT_NEAR(near.max.z, -0.07 + 0.5, 1e-6);
    const Aabb far = worldBox(unit, pose);  // relative to the world origin: 6 cm float steps
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LE(static_cast<double>(far.min[axis]), pose.position[axis] - 0.5) << axis;
        EXPECT_GE(static_cast<double>(far.max[axis]), pose.position[axis] + 0.5) << axis;
    }
    Scenario s = smallScenario();
    auto& teapots = std::get<TeapotFieldSpec>(s.sources[0].spec);
    teapots.region = {glm::vec3(999980, 0, 4950), glm::vec3(1000020, 5, 5000)};
    s.camera.keyframes = {{0.0, {999990.2, 2, 5010}, {1e6, 1, 4975}},
                          {2.0, {1000010.4, 2, 5040}, {1e6, 1, 4975}}};
    const Scene scene = buildScene(s);
    // The centre of the camera's keyframes, in whole metres: precision where the camera is.
    EXPECT_EQ(scene.culling_origin.x, 1000000.0);
    EXPECT_EQ(scene.culling_origin.z, 5025.0);
}

// A region is in double like the camera: 10^12 m out, the field is where the camera is aimed
// (in float, 10^12 rounds to 999,999,995,904: the scene landed 4 km away).
TEST(WorldBoxes, ARegionFarOutIsWhereTheScenarioPutsIt) {
    Scenario s = smallScenario();
    auto& teapots = std::get<TeapotFieldSpec>(s.sources[0].spec);
    teapots.region = {glm::dvec3(1e12, 0, 0), glm::dvec3(1e12 + 100, 5, 100)};
    s.camera.keyframes = {{0.0, {1e12 + 50, 3, 150}, {1e12 + 50, 1, 50}}};
    const Scene scene = buildScene(s);
    ASSERT_FALSE(scene.initial_poses.empty());
    for (const ObjectPose& p : scene.initial_poses) {
        EXPECT_GE(p.position.x, 1e12);
        EXPECT_LE(p.position.x, 1e12 + 100);
    }
}

// A far object does not pull the origin: one teapot 10^9 m away beside a field at the origin.
TEST(WorldBoxes, TheCullingOriginStaysWithTheCameraWhateverTheObjectsReach) {
    Scenario s = smallScenario();
    TeapotFieldSpec far;
    far.count = 1;
    far.region = {glm::vec3(1e9f, 0, 0), glm::vec3(1e9f + 1, 1, 1)};
    SceneSourceSpec& source = s.sources.emplace_back();
    source.type = SourceType::Teapots;
    source.spec.emplace<TeapotFieldSpec>(far);
    s.camera.keyframes = {{0.0, {3.4, 2, 6}, {0, 1, -20}}};
    const Scene scene = buildScene(s);
    EXPECT_EQ(scene.culling_origin, glm::dvec3(3, 2, 6));
}

// What a culler with needs_meshes gets (CullFrame::meshes): every mesh once, and per frame each
// object's transform into the culling frame, which puts its mesh inside its world box.
TEST(SharedWorld, MeshesForCullersAreFlatArraysAndTransformsFollowTheMovers) {
    Scenario s = smallScenario();
    auto& teapots = std::get<TeapotFieldSpec>(s.sources[0].spec);
    teapots.region = {glm::vec3(999980, 0, 4950), glm::vec3(1000020, 5, 5000)};
    s.camera.keyframes = {{0.0, {999990.2, 2, 5010}, {1e6, 1, 4975}}};
    s.frames = 3;
    const Scene scene = buildScene(s);
    SharedWorld world(scene, s);
    for (uint32_t frame = 0; frame < 3; ++frame) {
        world.advance();
        const CullMeshes& m = world.cullMeshes();
        ASSERT_EQ(m.meshes.size(), scene.meshes.size());
        ASSERT_EQ(m.object_mesh.size(), scene.objectCount());
        ASSERT_EQ(m.object_to_culling.size(), scene.objectCount());
        for (uint32_t o = 0; o < scene.objectCount(); o += 7) {
            const MeshRange& r = m.meshes[m.object_mesh[o]];
            EXPECT_EQ(r.index_count, scene.meshes[scene.object_mesh[o]].indices.size());
            const Aabb& box = world.state().boxes[o];
            for (uint32_t v = 0; v < r.vertex_count; v += 13) {
                const glm::vec4 p =
                    m.object_to_culling[o] * glm::vec4(m.positions[r.first_vertex + v], 1.0f);
                for (int axis = 0; axis < 3; ++axis) {
                    EXPECT_GE(p[axis], box.min[axis] - 1e-3f) << o;
                    EXPECT_LE(p[axis], box.max[axis] + 1e-3f) << o;
                }
            }
        }
    }
}

// The teapot's mesh is open, so it gets no inscribed occluder mesh: one line says which mesh,
// whose objects, and why; made once, before any frame's timing.
TEST(SharedWorld, AMeshWithoutAnInscribedOccluderIsNamedWithWhyInOneLine) {
    Scenario s = smallScenario();
    const Scene scene = buildScene(s);
    SharedWorld world(scene, s);
    world.advance();
    const CullMeshes& m = world.cullMeshes();
    const SharedWorld::OccluderMeshCost& cost = world.occluderMeshCost();
    EXPECT_EQ(cost.tried, 1u);
    EXPECT_EQ(cost.made, 0u);
    ASSERT_EQ(cost.refusals.size(), 1u);
    const std::string& line = cost.refusals[0];
    EXPECT_EQ(line.find('\n'), std::string::npos) << line;
    EXPECT_EQ(line.rfind("mesh 0 (of '", 0), 0u) << line;
    EXPECT_NE(line.find("has no inscribed occluder mesh: "), std::string::npos) << line;
    EXPECT_NE(line.find("not closed"), std::string::npos) << line;
    EXPECT_NE(line.find("own mesh in masked"), std::string::npos) << line;
    for (uint32_t o = 0; o < scene.objectCount(); ++o)
        EXPECT_EQ(m.object_occluder_mesh[o], kNoOccluderMesh) << o;
}

// A glTF node's own occluder mesh reaches the culler once checked against its object: a box
// inside the node's box stands in for it; one beside it is refused with a line naming the object,
// which then occludes with its own mesh.
TEST(SharedWorld, AGltfNodesOccluderMeshIsCheckedAgainstItsObject) {
    using nlohmann::json;
    using testing_gltf::GltfBuilder;
    using testing_gltf::TempDir;
    GltfBuilder b;
    auto box = [&](const std::string& name, float half, float dx) {
        std::vector<glm::vec3> corners;
        for (int i = 0; i < 8; ++i) {
            corners.emplace_back(dx + (i & 1 ? half : -half), i & 2 ? half : -half,
                                 i & 4 ? half : -half);
        }
        // Each face counter-clockwise seen from outside.
        const uint32_t quads[] = {0, 4, 6, 2, 1, 3, 7, 5, 0, 1, 5, 4,
                                  2, 6, 7, 3, 0, 2, 3, 1, 4, 5, 7, 6};
        std::vector<uint32_t> triangles;
        for (int q = 0; q < 24; q += 4) {
            triangles.insert(triangles.end(), {quads[q], quads[q + 1], quads[q + 2], quads[q],
                                               quads[q + 2], quads[q + 3]});
        }
        return b.mesh(name,
                      json::array({GltfBuilder::primitive(b.vec3(corners), b.indices(triangles))}));
    };
    const int outer = box("Outer", 1.0f, 0.0f), inner = box("Inner", 0.5f, 0.0f),
              beside = box("Beside", 0.5f, 3.0f);
    b.node({{"mesh", outer}, {"name", "Kept"}, {"extras", {{"occsim_occluder_mesh", inner}}}});
    b.node({{"mesh", outer},
            {"name", "Refused"},
            {"translation", {10, 0, 0}},
            {"extras", {{"occsim_occluder_mesh", beside}}}});
    TempDir dir;
    Scenario s = smallScenario();
    s.sources.clear();
    SceneSourceSpec& source = s.sources.emplace_back();
    source.type = SourceType::Gltf;
    GltfSourceSpec gltf;
    gltf.path = dir.write("model.gltf", b.text());
    source.spec.emplace<GltfSourceSpec>(gltf);
    s.movers.clear();
    const Scene scene = buildScene(s);
    ASSERT_EQ(scene.objectCount(), 2u);
    SharedWorld world(scene, s);
    world.advance();
    const CullMeshes& m = world.cullMeshes();
    ASSERT_NE(m.object_occluder_mesh[0], kNoOccluderMesh);
    EXPECT_EQ(m.meshes[m.object_occluder_mesh[0]].index_count, 36u);  // the inner box, whole
    EXPECT_EQ(m.object_occluder_mesh[1], kNoOccluderMesh);
    const SharedWorld::OccluderMeshCost& cost = world.occluderMeshCost();
    EXPECT_EQ(cost.tried, 2u);
    EXPECT_EQ(cost.made, 1u);
    ASSERT_EQ(cost.refusals.size(), 1u);
    EXPECT_NE(cost.refusals[0].find("the occluder mesh of 'Refused' (mesh "), std::string::npos)
        << cost.refusals[0];
    EXPECT_NE(cost.refusals[0].find("none of its 12 triangles lies inside its object; it "
                                    "occludes with its own mesh"),
              std::string::npos)
        << cost.refusals[0];
}

}  // namespace
}  // namespace occsim
