// What the fuzz targets feed their input to, shared by the libFuzzer executables
// (fuzz_scenario, fuzz_gltf; scripts/fuzz.sh) and by the regression test that replays every input
// a fuzzer ever found (tests/fuzz/regressions/<target>/). Bad input must end in the documented
// error (ScenarioError, GltfError); anything else (a crash, a hang, a sanitizer report, another
// exception escaping) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>

namespace occsim::fuzz {

// Parses the bytes as a scenario file. Returns true when it parsed, false on a ScenarioError.
bool scenarioInput(const uint8_t* data, size_t size);

// Loads the bytes as a glTF file (.glb when they start with the binary magic, .gltf otherwise)
// through the scene source. Returns true when it loaded, false on a GltfError.
bool gltfInput(const uint8_t* data, size_t size);

}  // namespace occsim::fuzz
