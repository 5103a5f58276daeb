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

}  // namespace

Expectations readExpectations(JsonObjectReader expect, const Scenario& scenario) {
    Expectations e;
    if (auto algorithms = expect.optionalArray("algorithms")) {
        algorithms->requireAtLeast(1, "algorithm");
        for (size_t i = 0; i < algorithms->size(); ++i) {
            const std::string name = algorithms->at(i).asEnum(algorithmNames());
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
    if (auto zero = expect.optionalArray("zero_error")) {
        for (size_t i = 0; i < zero->size(); ++i) {
            const std::string name = zero->at(i).asString();
            checkKnown(zero->at(i), name, e.algorithms);
            e.zero_error.push_back(name);
        }
    } else {
        // Algorithms that must never drop a visible pixel: zero error is expected of them unless
        // the scenario says otherwise.
        for (const std::string& name : e.algorithms) {
            if (findAlgorithm(name)->conservative) e.zero_error.push_back(name);
        }
    }
    if (const auto value = expect.optional("max_error_pixels")) {
        JsonObjectReader bounds = value->asObject();
        for (const auto& item : value->json().items()) {
            const JsonValueReader at = bounds.required(item.key());
            checkKnown(at, item.key(), e.algorithms);
            e.max_error_pixels[item.key()] = static_cast<int64_t>(at.asUnsigned());
        }
        bounds.finish();
    }
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
