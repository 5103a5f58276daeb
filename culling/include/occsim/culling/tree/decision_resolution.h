// A frame's decision records (occsim/culling/contract/decision_log.h) resolved per object, after
// the frame and outside its timing: the last record covering an object is its reason, except
// that a record on a node never overrides an object's own FrustumCulled. A record on a node's
// subtree covers every object stored in the subtree as the tree is after the frame (a culler does
// not change the tree). Objects no record covers get DecisionKind::NoReasonGiven: everything a
// plugin that records nothing left out or drew.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "occsim/culling/contract/decision_log.h"
#include "occsim/culling/tree/bsp_tree.h"

namespace occsim {

// out[o] = object o's decision (out is resized to the tree's object count); `stack` is scratch.
// Records naming a node or an object the tree does not have are ignored. With `subjects`, also
// subjects[o] = the subject of the record that decided object o (a node's subtree, a node's own
// objects, or the object itself), untagged where no record covers it: what `occsim why` follows
// to the node a decision rests on.
void resolveDecisions(const BspTree& tree, std::span<const DecisionRecord> records,
                      std::vector<Decision>& out, std::vector<uint32_t>& stack,
                      std::vector<QueryTag>* subjects = nullptr);

}  // namespace occsim
