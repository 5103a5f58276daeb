#include "sim/run/pixel_error.h"

#include <stdexcept>

namespace occsim {

PixelDifference classifyPixel(uint32_t truth_id, uint32_t truth_rank, uint32_t culled_id,
                              uint32_t culled_rank) {
    if (truth_id == culled_id) return PixelDifference::Same;
    // Background is infinitely far: an object and background never tie, whatever depth the
    // object's fragment stored (it can sit at the far plane's rank).
    if (truth_id == 0 || culled_id == 0) return PixelDifference::Error;
    const uint32_t apart =
        truth_rank > culled_rank ? truth_rank - culled_rank : culled_rank - truth_rank;
    return apart <= kDepthTieSteps ? PixelDifference::Tie : PixelDifference::Error;
}

PixelCounts comparePixels(std::span<const uint32_t> truth_ids,
                          std::span<const uint32_t> truth_ranks,
                          std::span<const uint32_t> culled_ids,
                          std::span<const uint32_t> culled_ranks,
                          std::span<const uint8_t> truth_stray, std::vector<uint8_t>* marks) {
    const size_t n = truth_ids.size();
    if (truth_ranks.size() != n || culled_ids.size() != n || culled_ranks.size() != n ||
        (!truth_stray.empty() && truth_stray.size() != n)) {
        throw std::invalid_argument("comparePixels: the ID and depth buffers differ in size");
    }
    if (marks) marks->assign(n, static_cast<uint8_t>(PixelDifference::Same));
    PixelCounts counts;
    for (size_t i = 0; i < n; ++i) {
        if (truth_ids[i] == culled_ids[i]) continue;  // the common case, decided without depth
        const PixelDifference d =
            !truth_stray.empty() && truth_stray[i]
                ? PixelDifference::Stray
                : classifyPixel(truth_ids[i], truth_ranks[i], culled_ids[i], culled_ranks[i]);
        counts.error += d == PixelDifference::Error;
        counts.tie += d == PixelDifference::Tie;
        counts.stray += d == PixelDifference::Stray;
        if (marks) (*marks)[i] = static_cast<uint8_t>(d);
    }
    return counts;
}

void attributePixels(std::span<const uint32_t> truth_ids, std::span<const uint8_t> truth_stray,
                     std::span<const uint32_t> culled_ids, std::span<const uint8_t> marks,
                     uint32_t objects, std::vector<ObjectPixels>& per_object) {
    const size_t n = truth_ids.size();
    if (culled_ids.size() != n || marks.size() != n ||
        (!truth_stray.empty() && truth_stray.size() != n)) {
        throw std::invalid_argument("attributePixels: the buffers differ in size");
    }
    per_object.assign(objects, ObjectPixels{});
    const auto at = [&](uint32_t id) -> ObjectPixels* {
        return id != 0 && id <= objects ? &per_object[id - 1] : nullptr;
    };
    for (size_t i = 0; i < n; ++i) {
        const bool stray = !truth_stray.empty() && truth_stray[i];
        ObjectPixels* truth = at(truth_ids[i]);
        if (truth && !stray) ++truth->truth;
        switch (static_cast<PixelDifference>(marks[i])) {
            case PixelDifference::Error:
                if (truth) {
                    ++truth->error;
                } else if (ObjectPixels* culled = at(culled_ids[i])) {
                    ++culled->error;
                }
                break;
            case PixelDifference::Tie:
                if (truth) ++truth->tie;
                break;
            case PixelDifference::Same:
            case PixelDifference::Stray:
                break;
        }
    }
}

}  // namespace occsim
