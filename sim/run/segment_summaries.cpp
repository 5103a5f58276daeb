#include "sim/run/segment_summaries.h"

namespace occsim {

std::vector<FrameStats> framesIn(const std::vector<FrameStats>& frames, const Segment& segment) {
    std::vector<FrameStats> in;
    for (const FrameStats& f : frames) {
        if (segment.contains(f.frame)) in.push_back(f);
    }
    return in;
}

RunSummary summarizeSegment(const std::string& label, const std::vector<FrameStats>& frames,
                            const Segment& segment, uint32_t warmup_frames,
                            const SegmentTallies* tallies, size_t k, bool measured_error) {
    RunSummary s = summarize(label, framesIn(frames, segment), warmup_frames);
    if (tallies && k < tallies->size()) {
        if (measured_error) addPopping(s, tallies->poppingRuns(k));
        addAnswerLatencies(s, tallies->answerLatencies(k));
    }
    return s;
}

std::vector<RunRecord> segmentRuns(const BenchResult& result, size_t k) {
    const Segment& segment = result.metadata.segments.at(k);
    std::vector<RunRecord> runs;
    runs.reserve(result.runs.size());
    for (const RunRecord& r : result.runs) {
        RunRecord s;
        s.summary = k < r.segments.size() ? r.segments[k] : RunSummary{};
        s.summary.label = r.summary.label;
        s.frames = framesIn(r.frames, segment);
        s.algorithm = r.algorithm;
        s.options = r.options;
        s.approximation = r.approximation;
        s.cost_model = r.cost_model;
        runs.push_back(std::move(s));
    }
    if (result.metadata.error_measured) markParetoFront(runs);
    return runs;
}

}  // namespace occsim
