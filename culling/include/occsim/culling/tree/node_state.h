// Per-node state kept beside a BspTree whose structure may change (local splits and merges): a
// flat array indexed by node, which follows the tree's structure without losing the state of
// nodes that did not change.
#pragma once

#include <cstdint>
#include <vector>

#include "occsim/culling/tree/bsp_tree.h"

namespace occsim {

template <class State>
class NodeStateArray {
  public:
    // Forgets everything: every node starts from State{}.
    void reset(const BspTree& tree) {
        state_.assign(tree.nodeCount(), State{});
        generation_.resize(tree.nodeCount());
        for (uint32_t n = 0; n < tree.nodeCount(); ++n) generation_[n] = tree.node(n).generation;
        version_ = tree.structureVersion();
        synced_ = true;
    }

    // Call before using the state in a frame: when the tree's structure changed, the slots of new
    // nodes start from State{} and the others keep theirs. O(1) when nothing changed.
    void sync(const BspTree& tree) {
        if (synced_ && version_ == tree.structureVersion() && state_.size() == tree.nodeCount()) {
            return;
        }
        if (!synced_) {
            reset(tree);
            return;
        }
        state_.resize(tree.nodeCount(), State{});
        generation_.resize(tree.nodeCount(), 0);
        for (uint32_t n = 0; n < tree.nodeCount(); ++n) {
            if (generation_[n] != tree.node(n).generation) {
                state_[n] = State{};
                generation_[n] = tree.node(n).generation;
            }
        }
        version_ = tree.structureVersion();
    }

    State& operator[](uint32_t node) { return state_[node]; }
    const State& operator[](uint32_t node) const { return state_[node]; }
    uint32_t size() const { return static_cast<uint32_t>(state_.size()); }

  private:
    std::vector<State> state_;
    std::vector<uint32_t> generation_;
    uint64_t version_ = 0;
    bool synced_ = false;
};

}  // namespace occsim
