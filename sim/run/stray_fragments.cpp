#include "sim/run/stray_fragments.h"

#include <algorithm>
#include <stdexcept>

namespace occsim {

void nearestLegitimateRanks(const GlRenderer& renderer, const ViewSetup& view,
                            std::span<const Aabb> boxes, std::vector<uint32_t>& out) {
    // View depth is -z after the view rotation of (point - eye): linear, so its minimum over a
    // box is at a corner, found per axis from the sign of the row's coefficient. In double: the
    // boxes may sit far from the origin.
    const glm::dvec3 row(-view.view_rotation[0][2], -view.view_rotation[1][2],
                         -view.view_rotation[2][2]);
    const glm::dvec3 offset = view.box_origin - view.eye;
    out.resize(boxes.size());
    for (size_t o = 0; o < boxes.size(); ++o) {
        const glm::dvec3 lo = glm::dvec3(boxes[o].min) + offset;
        const glm::dvec3 hi = glm::dvec3(boxes[o].max) + offset;
        double nearest = 0.0;
        for (int axis = 0; axis < 3; ++axis) {
            nearest += row[axis] * (row[axis] > 0.0 ? lo[axis] : hi[axis]);
        }
        out[o] = renderer.depthRankAt(nearest * (1.0 - kStrayDepthMargin));
    }
}

int64_t markStrayFragments(std::span<const uint32_t> ids, std::span<const uint32_t> ranks,
                           std::span<const uint32_t> nearest_rank, std::vector<uint8_t>& stray) {
    if (ranks.size() != ids.size()) {
        throw std::invalid_argument("markStrayFragments: the ID and depth buffers differ in size");
    }
    stray.assign(ids.size(), 0);
    int64_t count = 0;
    for (size_t i = 0; i < ids.size(); ++i) {
        const uint32_t id = ids[i];
        if (id == 0 || id > nearest_rank.size()) continue;
        if (ranks[i] > nearest_rank[id - 1]) {
            stray[i] = 1;
            ++count;
        }
    }
    return count;
}

}  // namespace occsim
