// What a scenario's seed changes in its scene. Generators lay their objects out by it, a glTF
// source's random copies and its animations' phases come from it, and movers pick their objects,
// their starts and their motions by it; a glTF level placed as its file lays it, with movers on
// listed objects at fixed speeds, may not change at all. Found by building the scene under both
// seeds and comparing (the static objects, which objects move, the movers over the first frames,
// the copies' phases), so that it stays true whatever a generator does with its seed: what the
// held-out variant of a tuning session (occtune) can say it tests.
#pragma once

#include <cstdint>
#include <string>

#include "sim/world/world.h"

namespace occsim {

struct SeedEffect {
    bool layout = false;      // the objects that do not move: places, meshes or their count
    bool which_move = false;  // the objects movers move
    bool motion = false;      // the movers' starts, directions, speeds, over the first frames
    bool phases = false;      // the glTF animations' phases

    bool any() const { return layout || which_move || motion || phases; }
    // "the layout of the scene and the movers' starts and motions", or "nothing".
    std::string text() const;
};

// Compares two scenes of one scenario built with different seeds, stepping both worlds `steps`
// times by dt_s.
SeedEffect seedEffect(const Scene& a, const Scene& b, double dt_s, uint32_t steps);

}  // namespace occsim
