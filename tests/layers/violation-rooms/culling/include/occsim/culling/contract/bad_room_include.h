// A deliberate room violation for the test layers.include_check_fails_on_a_room_violation (never
// compiled): the contract names the tree, it does not include it (the tree's traversal helpers
// build on the contract, so the contract sits below the tree).
#pragma once
#include "occsim/culling/tree/bsp_tree.h"
