// See shadow_error.h.
#include "sim/run/shadow_error.h"

#include <cstring>
#include <stdexcept>

namespace occsim {

namespace {

// A stored depth's rank among the floats (non-negative floats order as their bits).
uint32_t floatRank(float depth) {
    uint32_t rank = 0;
    std::memcpy(&rank, &depth, sizeof rank);
    return rank;
}

}  // namespace

ShadowPixelCounts compareShadowTerms(std::span<const uint32_t> truth_ids,
                                     std::span<const uint32_t> truth_texels,
                                     std::span<const uint32_t> culled_ids,
                                     std::span<const uint32_t> culled_texels,
                                     std::span<const float> truth_map,
                                     std::span<const float> culled_map) {
    const size_t n = truth_ids.size();
    if (truth_texels.size() != n || culled_ids.size() != n || culled_texels.size() != n ||
        truth_map.size() != culled_map.size()) {
        throw std::invalid_argument("compareShadowTerms: buffers of different sizes");
    }
    ShadowPixelCounts counts;
    for (size_t i = 0; i < n; ++i) {
        if (culled_ids[i] == 0 || culled_ids[i] != truth_ids[i]) continue;
        if ((truth_texels[i] != 0) == (culled_texels[i] != 0)) continue;
        const uint32_t texel = (truth_texels[i] != 0 ? truth_texels[i] : culled_texels[i]) - 1;
        if (texel < truth_map.size()) {
            const uint32_t a = floatRank(truth_map[texel]), b = floatRank(culled_map[texel]);
            if ((a > b ? a - b : b - a) <= kDepthTieSteps) {
                ++counts.tie;
                continue;
            }
        }
        ++counts.error;
    }
    return counts;
}

int64_t countMissedCasters(std::span<const uint32_t> shadow_pixels,
                           std::span<const uint8_t> drawn) {
    int64_t missed = 0;
    for (size_t o = 0; o < shadow_pixels.size(); ++o) {
        missed += shadow_pixels[o] > 0 && !(o < drawn.size() && drawn[o]);
    }
    return missed;
}

}  // namespace occsim
