// What the fuzz targets feed their input to, shared by the libFuzzer executables (one per target,
// fuzz_<name>, built from fuzz_target.cpp; scripts/fuzz.sh) and by the regression test that
// replays every input a fuzzer ever found (tests/fuzz/regressions/<name>/). Bad input must end in
// the documented error of its reader (ScenarioError, GltfError, ScriptError, BaselineError,
// TuneInputError, std::invalid_argument, RegistryError, MocrecError); anything else (a crash, a
// hang, a sanitizer report, another exception escaping, a broken promise of the reader) is a
// finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace occsim::fuzz {

// Each returns true when the input was accepted, false when it ended in the documented error.
using FuzzInput = bool (*)(const uint8_t* data, size_t size);

struct FuzzTarget {
    std::string_view name;  // fuzz_<name>, tests/fuzz/regressions/<name>/
    FuzzInput input;
    std::string_view what;  // one line: the reader it drives
};

// Every target, in the order scripts/fuzz.sh runs them.
const std::vector<FuzzTarget>& fuzzTargets();
const FuzzTarget* findFuzzTarget(std::string_view name);

// Parses the bytes as a scenario file.
bool scenarioInput(const uint8_t* data, size_t size);
// Loads the bytes as a glTF file (.glb when they start with the binary magic, .gltf otherwise)
// through the scene source.
bool gltfInput(const uint8_t* data, size_t size);
// Parses the bytes as a viewer script (occsim view --script).
bool viewScriptInput(const uint8_t* data, size_t size);
// Reads the bytes as a regression baseline file (*.baseline.json); an accepted baseline must
// read back the same from the text the program writes for it.
bool baselineInput(const uint8_t* data, size_t size);
// Reads the bytes as the tuner's sample log (samples.jsonl, occtune --resume) and derives what
// the tuner derives from it (samples, references, the reference noise).
bool sampleLogInput(const uint8_t* data, size_t size);
// Parses the bytes as an `occsim bench --sweep` string against every registered culler and plans
// the runs it asks for.
bool sweepInput(const uint8_t* data, size_t size);
// Parses the bytes as an `occsim bench --segments` string and places the segments on a run of 300
// frames at 30 a second; every placed one must hold a frame of the run.
bool segmentListInput(const uint8_t* data, size_t size);
// Reads the bytes as a `--culling` file and applies it to a scenario, with a plugin culler
// registered beside the built-ins, so that the file may set a plugin's options too.
bool cullingFileInput(const uint8_t* data, size_t size);
// Builds a plugin culler's options descriptor from the bytes (JSON rows: key, type, unit, min,
// max, default, tune, off, alternative_to) and offers it to a registry as a plugin would: refused
// with a RegistryError or accepted, and then its defaults and off values must be valid options.
bool pluginDescriptorInput(const uint8_t* data, size_t size);
// Reads the bytes as a Masked Occlusion Culling recording (.mocrec); an accepted frame must keep
// the header's promises: finite clip coordinates, every index below its batch's vertex count.
bool mocrecInput(const uint8_t* data, size_t size);

}  // namespace occsim::fuzz
