// The "segments" list of a scenario (docs/scenario-format.md#segments): each a name and either
// from/to in seconds or from_frame/to_frame in frames, placed on the scenario's frames here, so
// that a segment past the run is reported when the file is parsed, before any work.
#include "sim/scenario/parser_parts.h"

namespace occsim {

std::vector<SegmentSpec> readSegments(JsonObjectReader& top, const Scenario& scenario) {
    std::vector<SegmentSpec> specs;
    const auto list = top.optionalArray("segments");
    if (!list) return specs;
    for (size_t i = 0; i < list->size(); ++i) {
        JsonObjectReader item = list->at(i).asObject();
        SegmentSpec spec;
        spec.file = item.file();
        spec.pointer = item.pointer();
        const JsonValueReader name = item.required("name");
        spec.name = name.asString();
        if (const std::string problem = segmentNameProblem(spec.name); !problem.empty())
            name.failExpected(problem);
        for (const SegmentSpec& earlier : specs) {
            if (earlier.name == spec.name) {
                name.fail("'" + spec.name + "' already names the segment at " + earlier.pointer);
            }
        }
        const bool seconds = item.has("from") || item.has("to");
        const bool frames = item.has("from_frame") || item.has("to_frame");
        if (seconds && frames) {
            item.failHere(
                "expected from and to (seconds) or from_frame and to_frame (frames), not both");
        }
        if (!seconds && !frames) {
            item.failHere("expected from and to (seconds) or from_frame and to_frame (frames)");
        }
        spec.in_frames = frames;
        if (frames) {
            spec.from_frame = item.requiredUnsignedInteger("from_frame", 0, UINT32_MAX);
            spec.to_frame = item.requiredUnsignedInteger("to_frame", 0, UINT32_MAX);
            if (spec.to_frame <= spec.from_frame) {
                item.required("to_frame")
                    .failExpected("a frame after from_frame (" + std::to_string(spec.from_frame) +
                                  "; to_frame is exclusive)");
            }
        } else {
            spec.from_s = item.requiredNumber("from", NumberRange::atLeast(0.0));
            spec.to_s = item.requiredNumber("to", NumberRange::atLeast(0.0));
            if (!(spec.to_s > spec.from_s)) {
                item.required("to").failExpected("a time after from (" + formatNumber(spec.from_s) +
                                                 " s; to is exclusive)");
            }
        }
        item.finish();
        placeSegment(spec, scenario.frames, scenario.dt_s);  // throws at the key past the run
        specs.push_back(spec);
    }
    return specs;
}

}  // namespace occsim
