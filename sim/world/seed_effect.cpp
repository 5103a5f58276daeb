#include "sim/world/seed_effect.h"

#include <algorithm>
#include <vector>

namespace occsim {
namespace {

bool samePose(const ObjectPose& a, const ObjectPose& b) {
    return a.position == b.position && a.rotation == b.rotation && a.linear == b.linear;
}

// Per object: 1 when a step may move it (WorldState::moved).
std::vector<uint8_t> movedFlags(const WorldState& state, uint32_t objects) {
    std::vector<uint8_t> moved(objects, 0);
    for (uint32_t o : state.moved) moved[o] = 1;
    return moved;
}

// Where mover i has put what it moves: its object, or its whole copy's anchor.
const ObjectPose& moverPose(const WorldState& state, size_t i) {
    const Mover& m = state.movers[i];
    return m.copy >= 0 ? state.copies[static_cast<size_t>(m.copy)].anchor : state.poses[m.object];
}

}  // namespace

std::string SeedEffect::text() const {
    std::vector<std::string> parts;
    if (layout) parts.push_back("the layout of the scene");
    if (which_move) parts.push_back("which objects move");
    if (motion) parts.push_back("the movers' starts and motions");
    if (phases) parts.push_back("the phases of the glTF animations");
    if (parts.empty()) return "nothing";
    std::string out;
    for (size_t i = 0; i < parts.size(); ++i)
        out += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
    return out;
}

SeedEffect seedEffect(const Scene& a, const Scene& b, double dt_s, uint32_t steps) {
    SeedEffect e;
    if (a.objectCount() != b.objectCount() || a.object_mesh != b.object_mesh) {
        // Other objects altogether: no object can be compared with its namesake.
        e.layout = true;
        e.which_move = e.motion = !a.initial_movers.empty() || !b.initial_movers.empty();
        e.phases = !a.initial_copies.empty() || !b.initial_copies.empty();
        return e;
    }
    WorldState sa = initialState(a), sb = initialState(b);
    const std::vector<uint8_t> moved_a = movedFlags(sa, a.objectCount());
    e.which_move = moved_a != movedFlags(sb, b.objectCount()) ||
                   a.initial_movers.size() != b.initial_movers.size();
    for (uint32_t o = 0; o < a.objectCount() && !e.layout; ++o)
        e.layout = !moved_a[o] && !samePose(a.initial_poses[o], b.initial_poses[o]);
    if (a.initial_copies.size() != b.initial_copies.size()) {
        e.phases = true;
    } else {
        for (size_t c = 0; c < a.initial_copies.size(); ++c) {
            const ModelCopy &ca = a.initial_copies[c], &cb = b.initial_copies[c];
            e.phases |= ca.phase_s != cb.phase_s;
            // A copy its animations move stands where its seed put it (a random replication).
            e.layout |= !ca.rigid && !samePose(ca.anchor, cb.anchor);
        }
    }
    if (e.which_move) {
        e.motion = !a.initial_movers.empty() || !b.initial_movers.empty();
        return e;
    }
    for (uint32_t step = 0; step <= steps && !e.motion; ++step) {
        if (step > 0) {
            stepMovers(a, sa, dt_s);
            stepMovers(b, sb, dt_s);
        }
        for (size_t i = 0; i < sa.movers.size() && !e.motion; ++i)
            e.motion = !samePose(moverPose(sa, i), moverPose(sb, i));
    }
    return e;
}

}  // namespace occsim
