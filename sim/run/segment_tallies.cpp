#include "sim/run/segment_tallies.h"

namespace occsim {

void SegmentTallies::reset(const std::vector<Segment>& segments, uint32_t warmup_frames) {
    segments_ = segments;
    warmup_frames_ = warmup_frames;
    popping_.assign(segments.size(), PoppingCounter{});
    latencies_.assign(segments.size(), {});
}

void SegmentTallies::addMissing(uint32_t frame, const std::vector<uint8_t>& missing) {
    for (size_t k = 0; k < segments_.size(); ++k) {
        if (segments_[k].contains(frame)) popping_[k].addFrame(missing);
    }
}

void SegmentTallies::addLatencies(uint32_t frame, const std::vector<uint32_t>& latencies) {
    if (frame < warmup_frames_) return;
    for (size_t k = 0; k < segments_.size(); ++k) {
        if (!segments_[k].contains(frame)) continue;
        std::vector<uint64_t>& counts = latencies_[k];
        for (uint32_t latency : latencies) {
            if (latency >= counts.size()) counts.resize(size_t{latency} + 1, 0);
            ++counts[latency];
        }
    }
}

}  // namespace occsim
