#include "sim/scenario/segments.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "sim/scenario/errors.h"
#include "sim/scenario/json_reader.h"
#include "sim/scenario/number_text.h"

namespace occsim {
namespace {

constexpr size_t kMaxNameLength = 64;

[[noreturn]] void failSegment(const SegmentSpec& spec, const std::string& key,
                              const std::string& message) {
    if (!spec.file.empty()) throw ScenarioError(spec.file, spec.pointer + "/" + key, message);
    throw InputError("--segments: '" + spec.item + "': " + message);
}

// The first frame at or after time t (within kSegmentFrameTolerance of a frame), as a double so
// that a time far past any run cannot overflow.
double frameAtOrAfter(double t, double dt) { return std::ceil(t / dt - kSegmentFrameTolerance); }

// Computed times (frames * dt) to six digits: 40 * 0.0333333 is 1.33333 s, not 1.3333320000000002.
std::string seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g s", s);
    return text;
}

std::string runLength(uint32_t frames, double dt) {
    return std::to_string(frames) + " frames, " + formatNumber(dt) + " s apart: 0 to " +
           seconds(static_cast<double>(frames) * dt);
}

}  // namespace

std::string segmentNameProblem(std::string_view name) {
    const bool ok = !name.empty() && name.size() <= kMaxNameLength &&
                    std::all_of(name.begin(), name.end(), [](char c) {
                        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                               (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
                    });
    return ok ? "" : "a segment name of 1 to 64 letters, digits, '-', '_' and '.'";
}

Segment placeSegment(const SegmentSpec& spec, uint32_t frames, double dt) {
    Segment s;
    s.name = spec.name;
    s.origin = spec.file.empty() ? "--segments" : "scenario";
    if (spec.in_frames) {
        if (spec.from_frame >= frames) {
            failSegment(spec, "from_frame",
                        "expected a frame < " + std::to_string(frames) + " (the run has " +
                            std::to_string(frames) + " frames, from 0), got " +
                            std::to_string(spec.from_frame));
        }
        if (spec.to_frame > frames) {
            failSegment(spec, "to_frame",
                        "expected a frame <= " + std::to_string(frames) +
                            " (to_frame is exclusive; the run has " + std::to_string(frames) +
                            " frames), got " + std::to_string(spec.to_frame));
        }
        s.first_frame = static_cast<uint32_t>(spec.from_frame);
        s.end_frame = static_cast<uint32_t>(spec.to_frame);
        return s;
    }
    const double first = frameAtOrAfter(spec.from_s, dt), end = frameAtOrAfter(spec.to_s, dt);
    if (first >= frames) {
        failSegment(spec, "from",
                    "expected a time before the end of the run (" + runLength(frames, dt) +
                        "), got " + formatNumber(spec.from_s));
    }
    if (end > frames) {
        failSegment(spec, "to",
                    "expected a time <= " + seconds(static_cast<double>(frames) * dt) +
                        " (the end of the run: " + runLength(frames, dt) + "), got " +
                        formatNumber(spec.to_s));
    }
    if (end <= first) {
        failSegment(spec, "to",
                    "expected a segment that holds a frame, but no frame lies in [" +
                        formatNumber(spec.from_s) + " s, " + formatNumber(spec.to_s) +
                        " s) (frames are " + seconds(dt) + " apart)");
    }
    s.first_frame = static_cast<uint32_t>(first);
    s.end_frame = static_cast<uint32_t>(end);
    return s;
}

std::vector<SegmentSpec> parseSegmentList(const std::string& text) {
    std::vector<SegmentSpec> specs;
    const std::string expected = "expected NAME=FROM:TO (seconds) or NAME=fFROM:TO (frames)";
    size_t start = 0;
    while (true) {
        const size_t comma = std::min(text.find(',', start), text.size());
        SegmentSpec spec;
        spec.item = text.substr(start, comma - start);
        auto fail = [&](const std::string& message) -> void {
            throw std::invalid_argument("'" + spec.item + "': " + message);
        };
        const size_t eq = spec.item.find('=');
        if (spec.item.empty()) fail(expected + ", got an empty item");
        if (eq == std::string::npos) fail(expected + " (no '=')");
        spec.name = spec.item.substr(0, eq);
        if (const std::string problem = segmentNameProblem(spec.name); !problem.empty())
            fail("expected " + problem + " before '='");
        for (const SegmentSpec& earlier : specs) {
            if (earlier.name == spec.name) fail("'" + spec.name + "' is given twice");
        }
        std::string range = spec.item.substr(eq + 1);
        spec.in_frames = !range.empty() && range.front() == 'f';
        if (spec.in_frames) range.erase(0, 1);
        const size_t colon = range.find(':');
        if (colon == std::string::npos || range.find(':', colon + 1) != std::string::npos)
            fail(expected + " (one ':' between FROM and TO)");
        std::string from = range.substr(0, colon), to = range.substr(colon + 1);
        if (spec.in_frames && !to.empty() && to.front() == 'f') to.erase(0, 1);
        if (spec.in_frames) {
            int64_t a = 0, b = 0;
            const int64_t max = std::numeric_limits<uint32_t>::max();
            if (!parseInteger(from, a) || a < 0 || a > max || !parseInteger(to, b) || b < 0 ||
                b > max) {
                fail(expected + ": frames are whole numbers from 0");
            }
            if (b <= a) fail("expected TO after FROM (TO is exclusive), got " + to + " <= " + from);
            spec.from_frame = static_cast<uint64_t>(a);
            spec.to_frame = static_cast<uint64_t>(b);
        } else {
            double a = 0, b = 0;
            if (!parseFiniteNumber(from, a) || a < 0 || !parseFiniteNumber(to, b) || b < 0)
                fail(expected + ": seconds are numbers from 0");
            if (!(b > a)) {
                fail("expected TO after FROM (TO is exclusive), got " + formatNumber(b) +
                     " <= " + formatNumber(a));
            }
            spec.from_s = a;
            spec.to_s = b;
        }
        specs.push_back(spec);
        if (comma == text.size()) break;
        start = comma + 1;
    }
    return specs;
}

PlannedSegments planSegments(const std::vector<SegmentSpec>& scenario_segments,
                             uint32_t scenario_frames, const std::vector<SegmentSpec>& extra,
                             uint32_t run_frames, double dt) {
    PlannedSegments plan;
    for (const SegmentSpec& spec : scenario_segments) {
        Segment s = placeSegment(spec, scenario_frames, dt);
        const std::string what = "segment '" + s.name + "' (frames " +
                                 std::to_string(s.first_frame) + " to " +
                                 std::to_string(s.end_frame - 1) + ")";
        if (s.first_frame >= run_frames) {
            plan.notes.push_back(what + " lies past this run's " + std::to_string(run_frames) +
                                 " frames: left out");
            continue;
        }
        if (s.end_frame > run_frames) {
            s.end_frame = run_frames;
            s.note = "cut to frame " + std::to_string(run_frames - 1) + " by this run's " +
                     std::to_string(run_frames) + " frames";
            plan.notes.push_back(what + " " + s.note);
        }
        plan.segments.push_back(s);
    }
    for (const SegmentSpec& spec : extra) {
        for (const SegmentSpec& own : scenario_segments) {
            if (own.name == spec.name) {
                throw InputError("--segments: '" + spec.item + "': '" + spec.name +
                                 "' already names a segment of the scenario (" + own.file + ": " +
                                 own.pointer + ")");
            }
        }
        plan.segments.push_back(placeSegment(spec, run_frames, dt));
    }
    return plan;
}

}  // namespace occsim
