// Recorded flights as scenario files (sim/view/recorded_scenario.h): the loaded scenario with the
// flown path keyed at every frame, glTF paths found from the new folder, expected frames clamped.
#include <gtest/gtest.h>

#include <filesystem>

#include "sim/view/recorded_scenario.h"
#include "view_files.h"

namespace occsim {
namespace {

using namespace view_files;

std::vector<CameraKeyframe> flight(size_t frames, double dt) {
    std::vector<CameraKeyframe> keys;
    for (size_t i = 0; i < frames; ++i) {
        const double t = static_cast<double>(i) * dt;
        keys.push_back(
            {t, {0.1 * double(i), 2.0, 5.0 - 0.3 * double(i)}, {0.1 * double(i), 1.5, -5.0}});
    }
    return keys;
}

TEST(RecordedScenario, IsTheLoadedScenarioWithTheFlownPathKeyedAtEveryFrame) {
    const auto file = kScenarios / "small/teapots-small.json";
    const std::string text = readText(file);
    const Scenario original = parseScenarioFile(file);
    const auto dir = freshDir("recorded");
    const auto out = dir / "teapots-small-recorded-001.json";
    const std::vector<CameraKeyframe> keys = flight(3, original.dt_s);
    writeRecordedScenario(text, original, keys, out);

    const Scenario recorded = parseScenarioFile(out);
    EXPECT_EQ(recorded.name, "teapots-small-recorded-001");
    EXPECT_EQ(recorded.frames, 3u);
    EXPECT_EQ(recorded.warmup_frames, 2u);  // 5 in the original, clamped below the frame count
    EXPECT_FALSE(recorded.camera.loop);
    ASSERT_EQ(recorded.camera.keyframes.size(), 3u);
    for (size_t i = 0; i < keys.size(); ++i) {
        // Exactly the times a run samples the path at (frame * dt), and the flown poses.
        EXPECT_EQ(recorded.camera.keyframes[i].time_s, static_cast<double>(i) * original.dt_s);
        EXPECT_EQ(recorded.camera.keyframes[i].position, keys[i].position);
        EXPECT_EQ(recorded.camera.keyframes[i].target, keys[i].target);
    }
    EXPECT_EQ(recorded.camera.fov_y_deg, original.camera.fov_y_deg);
    EXPECT_EQ(recorded.camera.near_m, original.camera.near_m);
    EXPECT_EQ(recorded.camera.far_m, original.camera.far_m);
    EXPECT_EQ(recorded.dt_s, original.dt_s);
    EXPECT_EQ(recorded.seed, original.seed);
    EXPECT_EQ(recorded.width, original.width);
    EXPECT_EQ(recorded.movers.size(), original.movers.size());
    EXPECT_EQ(recorded.algorithm, original.algorithm);
    // The old baseline pins the old path: the new scenario gets its own, beside it.
    ASSERT_TRUE(recorded.expect.has_value());
    EXPECT_EQ(recorded.expect->baseline, dir / "teapots-small-recorded-001.baseline.json");
    EXPECT_EQ(recorded.expect->algorithms, original.expect->algorithms);

    // The author's key order stays.
    const std::string written = readText(out);
    EXPECT_LT(written.find("\"format_version\""), written.find("\"name\""));
    EXPECT_LT(written.find("\"viewport\""), written.find("\"camera\""));
    EXPECT_LT(written.find("\"camera\""), written.find("\"scene\""));
    if (!HasFailure()) std::filesystem::remove_all(dir);
}

TEST(RecordedScenario, GltfPathsStillFindTheirModelsFromTheNewFolder) {
    const auto file = kScenarios / "gltf-house.json";
    const Scenario original = parseScenarioFile(file);
    const auto dir = freshDir("recorded-gltf") / "elsewhere";
    const auto out = dir / "house-flight.json";
    writeRecordedScenario(readText(file), original, flight(2, original.dt_s), out);

    const Scenario recorded = parseScenarioFile(out);  // checks that the model exists
    const auto& was = std::get<GltfSourceSpec>(original.sources[0].spec).path;
    const auto& now = std::get<GltfSourceSpec>(recorded.sources[0].spec).path;
    EXPECT_TRUE(std::filesystem::equivalent(was, now)) << was << " vs " << now;
    EXPECT_EQ(recorded.name, "house-flight");
    EXPECT_EQ(recorded.frames, 2u);
    EXPECT_EQ(recorded.warmup_frames, 1u);
    if (!HasFailure()) std::filesystem::remove_all(dir.parent_path());
}

TEST(RecordedScenario, ExpectedFramesAreClampedToTheFlight) {
    const std::string text = R"({
  "format_version": 1,
  "frames": 50,
  "camera": {"orbit": {"center": [0, 0, -30], "radius": 45, "period": 20}, "near": 0.5},
  "scene": {"sources": [{"type": "teapots", "count": 10}]},
  "expect": {"frames": 40, "baseline": "somewhere.baseline.json"}
})";
    const auto dir = freshDir("recorded-expect");
    const Scenario original = parseScenarioText(text, dir / "orbit.json");
    const std::string written =
        recordedScenarioText(text, original, flight(4, original.dt_s), dir / "flight.json");
    const Scenario recorded = parseScenarioText(written, dir / "flight.json");
    ASSERT_TRUE(recorded.expect.has_value());
    EXPECT_EQ(recorded.expect->frames, 4u);
    EXPECT_EQ(recorded.expect->baseline, dir / "flight.baseline.json");
    EXPECT_EQ(recorded.camera.near_m, 0.5);
    EXPECT_EQ(recorded.camera.keyframes.size(), 4u);
    EXPECT_EQ(written.find("orbit"), std::string::npos);
    EXPECT_EQ(written.find("\"name\""), std::string::npos);  // absent before: the file name says it
}

}  // namespace
}  // namespace occsim
