// What a configuration's frames alone cannot give per segment, counted while it runs: popping
// (per object, runs of consecutive frames missing, which need the objects of every frame) and
// the answer latencies of every answer (frames.csv keeps only each frame's median). A Simulation
// feeds it every frame; a run without segments counts nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "sim/run/frame_stats.h"
#include "sim/scenario/segments.h"

namespace occsim {

class SegmentTallies {
  public:
    // Answers count only from warmup_frames on, as the whole run's do.
    void reset(const std::vector<Segment>& segments, uint32_t warmup_frames);

    // missing[o] != 0: object o was visible in ground truth and not drawn on `frame`.
    void addMissing(uint32_t frame, const std::vector<uint8_t>& missing);
    // The commands each of the frame's answers waited (Simulation::recordAnswerLatencies).
    void addLatencies(uint32_t frame, const std::vector<uint32_t>& latencies);

    size_t size() const { return segments_.size(); }
    // Popping within segment k: a run that began before the segment counts from its first frame.
    std::vector<uint32_t> poppingRuns(size_t k) const { return popping_[k].runs(); }
    // Counts per latency, as Simulation::answerLatencies() (addAnswerLatencies()).
    const std::vector<uint64_t>& answerLatencies(size_t k) const { return latencies_[k]; }

  private:
    std::vector<Segment> segments_;
    uint32_t warmup_frames_ = 0;
    std::vector<PoppingCounter> popping_;
    std::vector<std::vector<uint64_t>> latencies_;
};

}  // namespace occsim
