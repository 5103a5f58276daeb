// The "expect" block of a scenario (docs/regression.md), read with the rest of the file so that
// a mistake in it is reported when the scenario is parsed, whatever command reads it.
#include <algorithm>

#include "occsim/culling/registry/registry.h"
#include "sim/scenario/parser_parts.h"

namespace occsim {
namespace {

std::string algorithmList(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

void checkKnown(JsonValueReader at, const std::string& name, const std::vector<std::string>& run) {
    if (std::find(run.begin(), run.end(), name) == run.end()) {
        at.failExpected("an algorithm listed in /expect/algorithms (" + algorithmList(run) + ")");
    }
}

// The segment a check names: one of the scenario's, whole within the frames the run runs (a check
// over part of a segment would judge frames that never ran).
std::string segmentNamed(const JsonValueReader& at, const Scenario& scenario, uint32_t frames) {
    const std::string name = at.asString();
    std::string names;
    for (const SegmentSpec& spec : scenario.segments) {
        names += (names.empty() ? "" : ", ") + spec.name;
        if (spec.name != name) continue;
        const Segment s = placeSegment(spec, scenario.frames, scenario.dt_s);
        if (s.end_frame > frames) {
            at.fail("segment '" + name + "' (frames " + std::to_string(s.first_frame) + " to " +
                    std::to_string(s.end_frame - 1) + ") reaches past the " +
                    std::to_string(frames) + " frames this run runs (/expect/frames)");
        }
        return name;
    }
    at.failExpected(names.empty()
                        ? std::string("a segment, but the scenario names none (/segments)")
                        : "a segment named in /segments (" + names + ")");
}

// A zero_error entry: an algorithm's name (the whole run) or {"algorithm", "segment"}.
void readZeroError(const JsonValueReader& at, const Scenario& scenario, uint32_t frames,
                   Expectations& e) {
    if (!at.json().is_object() && !at.json().is_string())
        at.failExpected("an algorithm's name or {\"algorithm\": ..., \"segment\": ...}");
    if (at.json().is_string()) {
        const std::string name = at.asString();
        checkKnown(at, name, e.algorithms);
        e.zero_error.push_back(name);
        return;
    }
    JsonObjectReader entry = at.asObject();
    const JsonValueReader algorithm = entry.required("algorithm");
    SegmentErrorExpectation z{algorithm.asString(), "", std::nullopt};
    checkKnown(algorithm, z.algorithm, e.algorithms);
    z.segment = segmentNamed(entry.required("segment"), scenario, frames);
    entry.finish();
    e.segment_errors.push_back(z);
}

// max_error_pixels as an object ({"async": 2000}: whole-run bounds) or as a list of
// {"algorithm", "max", "segment"} (a missing segment: the whole run).
void readMaxErrorPixels(const JsonValueReader& value, const Scenario& scenario, uint32_t frames,
                        Expectations& e) {
    if (!value.json().is_array() && !value.json().is_object()) {
        value.failExpected(
            "an object of bounds ({\"async\": 2000}) or a list of {\"algorithm\", "
            "\"max\", \"segment\"}");
    }
    if (value.json().is_object()) {
        JsonObjectReader bounds = value.asObject();
        for (const auto& item : value.json().items()) {
            const JsonValueReader at = bounds.required(item.key());
            checkKnown(at, item.key(), e.algorithms);
            e.max_error_pixels[item.key()] = static_cast<int64_t>(at.asUnsigned());
        }
        bounds.finish();
        return;
    }
    const JsonArrayReader list = value.asArray();
    for (size_t i = 0; i < list.size(); ++i) {
        JsonObjectReader entry = list.at(i).asObject();
        const JsonValueReader algorithm = entry.required("algorithm");
        const std::string name = algorithm.asString();
        checkKnown(algorithm, name, e.algorithms);
        const auto max = static_cast<int64_t>(entry.required("max").asUnsigned());
        if (const auto segment = entry.optional("segment")) {
            e.segment_errors.push_back({name, segmentNamed(*segment, scenario, frames), max});
        } else {
            if (e.max_error_pixels.count(name)) {
                algorithm.fail("'" + name + "' has a whole-run bound already");
            }
            e.max_error_pixels[name] = max;
        }
        entry.finish();
    }
}

}  // namespace

Expectations readExpectations(JsonObjectReader expect, const Scenario& scenario) {
    Expectations e;
    if (auto algorithms = expect.optionalArray("algorithms")) {
        algorithms->requireAtLeast(1, "algorithm");
        for (size_t i = 0; i < algorithms->size(); ++i) {
            const std::string name = algorithms->at(i).asEnum(cullerNames());
            if (std::find(e.algorithms.begin(), e.algorithms.end(), name) != e.algorithms.end()) {
                algorithms->at(i).fail("'" + name + "' is listed twice");
            }
            e.algorithms.push_back(name);
        }
    } else {
        const std::string reference(speedupReference().name);
        e.algorithms = {reference};
        if (scenario.algorithm != reference) e.algorithms.push_back(scenario.algorithm);
    }
    e.deterministic_latency = static_cast<uint32_t>(
        expect.unsignedInteger("deterministic_latency", e.deterministic_latency, 0, 1'000'000));
    if (expect.has("frames")) {
        e.frames =
            static_cast<uint32_t>(expect.requiredUnsignedInteger("frames", 1, scenario.frames));
    }
    const uint32_t frames = e.frames.value_or(scenario.frames);
    if (auto zero = expect.optionalArray("zero_error")) {
        for (size_t i = 0; i < zero->size(); ++i) readZeroError(zero->at(i), scenario, frames, e);
    } else {
        // Algorithms that must never drop a visible pixel: zero error is expected of them unless
        // the scenario says otherwise.
        for (const std::string& name : e.algorithms) {
            if (findCuller(name)->conservative) e.zero_error.push_back(name);
        }
    }
    if (const auto value = expect.optional("max_error_pixels"))
        readMaxErrorPixels(*value, scenario, frames, e);
    if (auto ratios = expect.optionalArray("ratios")) {
        for (size_t i = 0; i < ratios->size(); ++i) {
            JsonObjectReader r = ratios->at(i).asObject();
            RatioExpectation ratio;
            ratio.algorithm = r.required("algorithm").asString();
            checkKnown(r.required("algorithm"), ratio.algorithm, e.algorithms);
            ratio.reference = r.required("reference").asString();
            checkKnown(r.required("reference"), ratio.reference, e.algorithms);
            ratio.max = r.requiredNumber("max", NumberRange::greaterThan(0.0));
            ratio.tolerance = r.number("tolerance", 0.0, NumberRange::closed(0.0, 10.0));
            if (const auto segment = r.optional("segment"))
                ratio.segment = segmentNamed(*segment, scenario, frames);
            r.finish();
            e.ratios.push_back(ratio);
        }
    }
    const std::string baseline =
        expect.string("baseline", scenario.file.stem().string() + ".baseline.json");
    if (baseline.empty()) expect.fail("baseline", "expected a file name, got an empty string");
    e.baseline = scenario.file.parent_path() / baseline;
    expect.finish();
    return e;
}

}  // namespace occsim
