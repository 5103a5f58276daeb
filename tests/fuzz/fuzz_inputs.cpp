#include "fuzz_inputs.h"

#include "sim/scenario/scenario.h"
#include "sim/scene/gltf_source.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace occsim::fuzz {

bool scenarioInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const Scenario scenario = parseScenarioText(text, "fuzz/scenario.json");
        return !scenario.sources.empty();
    } catch (const ScenarioError&) {
        return false;
    }
}

bool gltfInput(const uint8_t* data, size_t size) {
    // tinygltf reads files; one private folder per process keeps parallel fuzzing jobs apart.
    static const std::filesystem::path dir = [] {
        const auto d = std::filesystem::temp_directory_path() /
                       ("occsim-fuzz-gltf-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    GltfSourceSpec spec;
    spec.path = dir / (binary ? "input.glb" : "input.gltf");
    std::ofstream(spec.path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    try {
        return !loadGltfSource(spec, 1).objects.empty();
    } catch (const GltfError&) {
        return false;
    }
}

}  // namespace occsim::fuzz
