// Readers of scenario sections that live in their own files, so that each scene source and the
// culling options can grow without touching the core parser. Each reads the keys it owns from an
// object reader; the caller calls finish() (so unknown keys stay errors).
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sim/scenario/json_reader.h"
#include "sim/scenario/scenario.h"

namespace occsim {

// The largest value a uint32_t field of a scenario can take.
inline constexpr uint64_t kMaxUint32 = std::numeric_limits<uint32_t>::max();

// scenario_parser.cpp: a file's text; a ScenarioError says why it cannot be read.
std::string readScenarioFileText(const std::filesystem::path& file);

// scenario_parser.cpp: {"min": [x,y,z], "max": [x,y,z]}, min <= max, float-representable.
WorldBox readRegion(const JsonValueReader& value);

// parse_culling.cpp: the "culling" section (algorithm and per-algorithm options).
void readCulling(JsonObjectReader& top, Scenario& s);

// parse_sources.cpp: the keys of each source type besides "type". Paths resolve against
// the scenario file's folder.
TeapotFieldSpec readTeapotField(JsonObjectReader& source);
GltfSourceSpec readGltfSource(JsonObjectReader& source, const std::filesystem::path& scenario_dir);
CitySpec readCity(JsonObjectReader& source);
LibrarySpec readLibrary(JsonObjectReader& source);
PlantSpec readPlant(JsonObjectReader& source);

// parse_views.cpp: the "lights" list and the "stereo" object (absent: none).
std::vector<LightSpec> readLights(JsonObjectReader& top);
std::optional<StereoSpec> readStereo(JsonObjectReader& top);

// parse_segments.cpp: the "segments" list, placed on the scenario's frames (frames and dt read).
std::vector<SegmentSpec> readSegments(JsonObjectReader& top, const Scenario& scenario);

// parse_expectations.cpp: the "expect" block; reads the run settings and the culling section of
// `scenario`, so it is called after them.
Expectations readExpectations(JsonObjectReader expect, const Scenario& scenario);

}  // namespace occsim
