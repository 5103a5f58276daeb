// The node a decision rests on, as the simulation keeps it per object and frame and objects.sqlite
// stores it (docs/objects.md, decisions.node_kind): the numbers are stored, never renumber.
#pragma once

#include <cstdint>

namespace occsim {

enum class DecidingNode : uint8_t {
    None = 0,         // decided for the object itself, or by no record
    Leaf = 1,         // with a leaf (its objects)
    Subtree = 2,      // with an inner node's subtree
    NodeObjects = 3,  // with the objects stored in an inner node itself
};

}  // namespace occsim
