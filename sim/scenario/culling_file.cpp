#include "sim/scenario/culling_file.h"

#include "occsim/culling/registry/registry.h"
#include "sim/scenario/parser_parts.h"

namespace occsim {
namespace {

constexpr uint64_t kCullingFileFormatVersion = 1;

// A tuned file ("tuned_for": NAME, as occtune writes it) is one culler's confirmed setting: NAME
// is a loaded culler, culling.algorithm is NAME, no other culler's options are in it, nor the
// approximation knobs every querying culler shares, and its cost model is scoped to NAME alone
// (a shared one would change every culler that weighs costs).
// Checked before the culling section, so that a culler not loaded is named as such.
void checkTunedFor(JsonObjectReader& top) {
    const std::optional<JsonValueReader> marker = top.optional("tuned_for");
    if (!marker) return;
    if (!marker->json().is_string()) marker->failExpected("the name of the culler tuned");
    const std::string culler = marker->asString();
    if (!findCuller(culler)) {
        marker->failExpected("a loaded culler (" + cullerNameList() +
                             "; a plugin's culler needs its --plugin FILE)");
    }
    JsonObjectReader section = top.required("culling").asObject();
    const std::string tuned = "\"" + culler + "\" (the culler this file was tuned for)";
    const JsonValueReader algorithm = section.required("algorithm");
    if (!(algorithm.json().is_string() && algorithm.asString() == culler))
        algorithm.failExpected(tuned);
    // The approximation knobs apply to every culler that issues queries: in a tuned file they
    // would turn the other cullers of a run approximate too.
    for (const char* shared : {"threshold_pixels", "stale_results"}) {
        if (const auto knob = section.optional(shared)) {
            knob->fail(std::string("a tuned file changes ") + tuned +
                       " alone; this knob applies to every culler that issues queries (set it "
                       "in the scenario or a culling file without tuned_for)");
        }
    }
    for (const CullerRow* other : cullerRows()) {
        if (other->name == culler) continue;
        if (const auto options = section.optional(other->name)) {
            options->fail("expected the options of " + tuned + " only, not " + other->name + "'s");
        }
    }
    if (const auto cost = section.optional("cost_model")) {
        const Json& cullers = cost->json().is_object() && cost->json().contains("cullers")
                                  ? cost->json().at("cullers")
                                  : Json();
        if (!(cullers.is_array() && cullers.size() == 1 && cullers[0] == culler)) {
            cost->fail("expected \"cullers\": [\"" + culler +
                       "\"]: a tuned cost model is for the culler tuned alone");
        }
    }
}

// The whole file through the strict readers: the version, the required "culling" object, an
// optional "tuned_for" (checkTunedFor), and nothing else.
void readInto(const CullingFile& culling, Scenario& scenario) {
    const std::string name = culling.file.string();
    JsonObjectReader top(culling.json, "", name);
    const JsonValueReader version = top.required("format_version");
    if (!(version.json().is_number() && version.json() == kCullingFileFormatVersion)) {
        version.failExpected(std::to_string(kCullingFileFormatVersion) +
                             " (the only format_version this program reads)");
    }
    top.required("culling").asObject();  // present, and an object
    checkTunedFor(top);
    readCulling(top, scenario);
    top.finish();
}

}  // namespace

CullingFile readCullingFile(const std::filesystem::path& file) {
    CullingFile culling{file, parseStrictJson(readScenarioFileText(file), file.string())};
    Scenario probe;
    readInto(culling, probe);
    return culling;
}

void applyCullingFile(const CullingFile& culling, Scenario& scenario) {
    readInto(culling, scenario);
}

}  // namespace occsim
