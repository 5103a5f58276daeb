// Pieces the coherent hierarchical cullers (CHC and CHC++) share: the front-to-back traversal
// queue ordered by distance, and the boxes a query on a node's own objects covers.
//
// Both papers allow a depth-first stack for kD-trees, but recommend the distance-ordered
// (breadth-first) priority queue: it processes the scene in depth layers, so nodes whose queries
// are in flight at the same time rarely occlude each other (Bittner & Wimmer, "Front-to-back
// scene traversal"), and CHC++ is written against it.
#pragma once

#include "culling/bsp_tree.h"
#include "culling/frustum.h"
#include "culling/traversal.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace occsim {

// A min-heap of nodes keyed by the distance from the eye to their bounds. The storage is reused
// from frame to frame, so a steady state allocates nothing.
class DistanceQueue {
public:
    void clear() { heap_.clear(); }
    bool empty() const { return heap_.empty(); }

    void push(const BspTree& tree, NodeVisit visit, glm::vec3 eye) {
        heap_.push_back({distanceSquared(tree.bounds(visit.node), eye), visit});
        std::push_heap(heap_.begin(), heap_.end(), Later{});
    }

    void pushChildren(const BspTree& tree, uint32_t node, glm::vec3 eye, bool inside_frustum) {
        const BspNode& n = tree.node(node);
        if (n.isLeaf()) return;
        push(tree, {n.child[0], inside_frustum}, eye);
        push(tree, {n.child[1], inside_frustum}, eye);
    }

    NodeVisit pop() {
        std::pop_heap(heap_.begin(), heap_.end(), Later{});
        const NodeVisit visit = heap_.back().visit;
        heap_.pop_back();
        return visit;
    }

private:
    struct Entry {
        float distance_squared;
        NodeVisit visit;
    };
    // Orders the heap so that the nearest node comes out first; ties go to the lower node index,
    // so the order never depends on the heap's history.
    struct Later {
        bool operator()(const Entry& a, const Entry& b) const {
            if (a.distance_squared != b.distance_squared) {
                return a.distance_squared > b.distance_squared;
            }
            return a.visit.node > b.visit.node;
        }
    };
    std::vector<Entry> heap_;
};

// Appends the boxes of the objects stored in `node` itself that pass the frustum (the objects
// drawNodeObjects() would draw) and returns how many. In an inner node these are the straddlers:
// the node's own bounds cover its whole subtree, so a query on them would say nothing about the
// straddlers alone; the boxes of exactly the drawn objects do.
inline uint32_t appendOwnObjectBoxes(const BspTree& tree, uint32_t node, const Frustum& frustum,
                                     bool inside_frustum, std::vector<Aabb>& out) {
    uint32_t count = 0;
    for (uint32_t o = tree.firstObject(node); o != BspTree::kNone; o = tree.nextObject(o)) {
        const Aabb& box = tree.objectBox(o);
        if (inside_frustum || classify(frustum, box) != FrustumTest::Outside) {
            out.push_back(box);
            ++count;
        }
    }
    return count;
}

}  // namespace occsim
