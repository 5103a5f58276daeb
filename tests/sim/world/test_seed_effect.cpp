// What another seed changes in a scene (sim/world/seed_effect.h), said in words.
#include <gtest/gtest.h>

#include "sim/world/seed_effect.h"
#include "small_scenario.h"

namespace occsim {
namespace {

using testing::smallScenario;

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

}  // namespace
}  // namespace occsim
