// Segments: named stretches of a run ("the corner", "while the truck passes") over which every
// figure of a run is also given (docs/scenario-format.md#segments). A scenario names them in
// "segments"; `occsim run` and `bench` add more with --segments. Either form gives seconds of the
// camera path (frame f is at f * dt from the start of the run, whatever start_time says) or
// frames; in both, `from` is inclusive and `to` exclusive, so back-to-back segments share no frame
// and 4.0 to 4.6 s at 30 frames a second is frames 120 to 137, the same as frames 120:138.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace occsim {

// A segment as written, before it is placed on a run's frames.
struct SegmentSpec {
    std::string name;
    bool in_frames = false;
    double from_s = 0.0, to_s = 0.0;        // seconds, when !in_frames
    uint64_t from_frame = 0, to_frame = 0;  // frames, when in_frames
    // Where it was written, for messages: the scenario file and the segment's JSON pointer
    // ("/segments/2"), or, for --segments (file empty), its item as typed ("corner=4:4.6").
    std::string file, pointer, item;
};

// A segment on a run's frames: [first_frame, end_frame), at least one frame.
struct Segment {
    std::string name;
    uint32_t first_frame = 0;
    uint32_t end_frame = 0;  // one past its last frame
    std::string origin;      // "scenario" or "--segments"
    std::string note;        // how a shortened run cut it ("" when whole)
    uint32_t frames() const { return end_frame - first_frame; }
    bool contains(uint32_t frame) const { return frame >= first_frame && frame < end_frame; }
};

// A time within this share of a frame of a frame's own time counts as that frame's time, so that
// 4.0 s with dt 0.0333333 (frame 120 is at 3.999996 s) starts at frame 120.
inline constexpr double kSegmentFrameTolerance = 1e-3;

// Empty when `name` can name a segment (1 to 64 letters, digits, '-', '_' and '.': a name is
// written in --segments, in check names and in file names); otherwise what was expected.
std::string segmentNameProblem(std::string_view name);

// The frames of `spec` in a run of `frames` frames `dt` seconds apart. Throws ScenarioError at
// the key it is about (for a scenario's segment) or InputError "--segments: 'ITEM': ..." when it
// starts or ends past the run or holds no frame.
Segment placeSegment(const SegmentSpec& spec, uint32_t frames, double dt);

// The text of --segments: NAME=FROM:TO in seconds or NAME=fFROM:TO in frames, comma-separated
// ("corner=4.0:4.6,truck=f120:138"). Throws std::invalid_argument naming the item and what was
// expected: a malformed item, a bad name, `to` not after `from`, a name given twice.
std::vector<SegmentSpec> parseSegmentList(const std::string& text);

// The segments of one run: the scenario's, placed on its own frame count and then cut to a run
// shortened by --frames or expect.frames (each cut or dropped one with a note: nothing of it
// lost silently), then the extra ones (--segments), which must fit the run as it is. Throws
// InputError for an extra segment that does not fit or whose name the scenario already uses.
struct PlannedSegments {
    std::vector<Segment> segments;
    std::vector<std::string> notes;  // one line per segment a shortened run cut or dropped
};
PlannedSegments planSegments(const std::vector<SegmentSpec>& scenario_segments,
                             uint32_t scenario_frames, const std::vector<SegmentSpec>& extra,
                             uint32_t run_frames, double dt);

}  // namespace occsim
