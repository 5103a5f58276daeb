#include "sim/run/verdict_log.h"

#include "sim/run/simulation.h"

namespace occsim {

void VerdictLog::record(uint32_t frame, std::span<const uint8_t> verdicts) {
    if (overflowed_) return;
    FrameVerdicts kept;
    for (size_t o = 0; o < verdicts.size(); ++o) {
        const auto verdict = static_cast<ObjectVerdict>(verdicts[o]);
        if (verdict == ObjectVerdict::Missed) kept.missed.push_back(static_cast<uint32_t>(o));
        if (verdict == ObjectVerdict::DrawnHidden)
            kept.drawn_hidden.push_back(static_cast<uint32_t>(o));
    }
    const size_t cost =
        sizeof(FrameVerdicts) + (kept.missed.size() + kept.drawn_hidden.size()) * sizeof(uint32_t);
    if (bytes_ + cost > budget_bytes_) {
        // Later frames would make a log with holes in it: it ends here.
        overflowed_ = true;
        return;
    }
    bytes_ += cost;
    if (frame_index_.size() <= frame) frame_index_.resize(size_t{frame} + 1, 0);
    frames_.push_back(std::move(kept));
    frame_index_[frame] = static_cast<uint32_t>(frames_.size());
}

const FrameVerdicts* VerdictLog::at(uint32_t frame) const {
    if (frame >= frame_index_.size() || frame_index_[frame] == 0) return nullptr;
    return &frames_[frame_index_[frame] - 1];
}

}  // namespace occsim
