// Procedural scene generators modelled on the test scenes of the papers. Each is seeded and
// scalable, deterministic for a given spec and seed, and returns a SourceOutput (meshes, placed
// objects, lanes for movers). Units: metres. See docs/scenario-generators.md for the scenario keys.
#pragma once

#include <cstdint>

#include "sim/scenario/scene_specs.h"
#include "sim/scene/scene_source.h"

namespace occsim {

SourceOutput generateCity(const CitySpec& spec, uint64_t seed);
SourceOutput generateLibrary(const LibrarySpec& spec, uint64_t seed);
SourceOutput generatePlant(const PlantSpec& spec, uint64_t seed);

}  // namespace occsim
