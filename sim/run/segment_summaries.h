// Every figure of a run over each of its segments: a segment's summary is summarize() over that
// segment's frames (the warm-up frames among them left out of its timing, as for the whole run),
// with its own popping and answer latencies (SegmentTallies), aggregated over repetitions by
// aggregateRepetitions() as the whole run's are.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sim/run/results.h"
#include "sim/run/segment_tallies.h"

namespace occsim {

// The frames of `frames` (a configuration's, frame by frame) that lie in the segment.
std::vector<FrameStats> framesIn(const std::vector<FrameStats>& frames, const Segment& segment);

// One repetition's summary over segment k of `tallies`' segments.
RunSummary summarizeSegment(const std::string& label, const std::vector<FrameStats>& frames,
                            const Segment& segment, uint32_t warmup_frames,
                            const SegmentTallies* tallies, size_t k, bool measured_error);

// The run as it went over segment k of result.metadata.segments: each record's summary is its
// summary over the segment and its frames are the segment's (first repetition), the Pareto front
// marked over the segment's figures; ready for comparisonTable(), speedupOverReference() and
// ratioToOracle(), which then give the segment's speedups.
std::vector<RunRecord> segmentRuns(const BenchResult& result, size_t k);

}  // namespace occsim
