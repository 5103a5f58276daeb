// See visible_receivers.h.
#include "sim/run/visible_receivers.h"

#include <algorithm>
#include <cstring>
#include <glm/glm.hpp>

namespace occsim {
namespace {

constexpr uint32_t kMax24 = 0xFFFFFFu;

// The normalised-device z of a stored depth rank (GlRenderer::readDepthRanks' inverse).
double ndcZOfRank(uint32_t rank, DepthConvention depth) {
    if (depth == DepthConvention::ReverseFloat) {
        float stored = 0.0f;
        std::memcpy(&stored, &rank, sizeof stored);
        return stored;  // clip control 0..1: the stored value is z
    }
    const double window = double(kMax24 - std::min(rank, kMax24)) / double(kMax24);
    return 2.0 * window - 1.0;
}

}  // namespace

void addVisibleReceivers(std::span<const uint32_t> depth_ranks, uint32_t width, uint32_t height,
                         const ViewSetup& camera, DepthConvention depth, double margin_m,
                         ReceiverMask& mask) {
    const glm::dmat4 unproject = glm::inverse(glm::dmat4(camera.projection));
    const glm::dmat3 view_to_world = glm::transpose(glm::dmat3(camera.view_rotation));
    const uint32_t nearest = depth == DepthConvention::ReverseFloat ? 0x3F800000u : kMax24;
    auto viewPoint = [&](double x, double y, uint32_t rank) {
        const glm::dvec4 v = unproject * glm::dvec4(x, y, ndcZOfRank(rank, depth), 1.0);
        return glm::dvec3(v) / v.w;
    };
    for (uint32_t row = 0; row < height; ++row) {
        const double y = (row + 0.5) / height * 2.0 - 1.0;
        for (uint32_t col = 0; col < width; ++col) {
            const uint32_t rank = depth_ranks[size_t{row} * width + col];
            if (rank == 0) continue;  // background
            const double x = (col + 0.5) / width * 2.0 - 1.0;
            const glm::dvec3 p = viewPoint(x, y, rank);
            // The neighbouring stored values, one step farther and one nearer.
            double rounding = glm::length(viewPoint(x, y, rank - 1) - p);
            if (rank < nearest)
                rounding = std::max(rounding, glm::length(viewPoint(x, y, rank + 1) - p));
            mask.addReceiver(camera.eye + view_to_world * p, margin_m + rounding);
        }
    }
}

}  // namespace occsim
