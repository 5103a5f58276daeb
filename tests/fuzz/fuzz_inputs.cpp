#include "fuzz_inputs.h"

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "occsim/culling/registry/registry.h"
#include "sim/regress/regress.h"
#include "sim/run/run_config.h"
#include "sim/scenario/culling_file.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/segments.h"
#include "sim/scene/gltf_source.h"
#include "sim/scene/mocrec.h"
#include "sim/view/view_script.h"
#include "tune/errors.h"
#include "tune/sample_log.h"

namespace occsim::fuzz {
namespace {

namespace fs = std::filesystem;

std::string textOf(const uint8_t* data, size_t size) {
    return std::string(reinterpret_cast<const char*>(data), size);
}

// The readers that take a path get the bytes as a file; one private folder per process keeps
// parallel fuzzing jobs (and test runs of other checkouts) apart.
fs::path inputFile(const std::string& name, const std::string& bytes) {
    static const fs::path dir = [] {
        const auto d = fs::temp_directory_path() / ("occsim-fuzz-" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    const fs::path file = dir / name;
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return file;
}

// A finding that is no crash: a reader broke a promise its header makes.
[[noreturn]] void brokenPromise(const std::string& what) {
    throw std::logic_error("fuzz: " + what);
}

// The plugin culler whose options a --culling file may set (cullingFileInput): every option type,
// an unbounded number, an alternative pair and a validate hook, registered once per process.
void registerFuzzPlugin() {
    static const bool registered = [] {
        CullerRow t;
        t.name = "fuzz-plugin";
        t.summary = "a plugin culler for the fuzz targets";
        t.source = "fuzz_inputs.cpp";
        const double inf = std::numeric_limits<double>::infinity();
        t.options = {
            switchable(booleanOption("enabled", true, "a switch"), 0.0),
            tunable(integerOption("budget", "objects", 1, 1000, 10, "a count"), 1, 100),
            alternativeTo(switchable(numberOption("radius", "m", 0.0, inf, 0.0, "a distance"), 0.0),
                          "angle"),
            alternativeTo(switchable(numberOption("angle", "", 0.0, 1.0, 0.5, "a share"), 0.0),
                          "radius"),
        };
        t.validate = [](const OptionValues& v) -> std::string {
            return v.number("radius") > 0.0 && v.number("angle") > 0.0 ? "radius and angle: one"
                                                                       : "";
        };
        t.factory = [](const CullerContext&) -> std::unique_ptr<Culler> { return nullptr; };
        cullerRegistry().add(std::move(t));
        return true;
    }();
    (void)registered;
}

// One descriptor row from the fuzz JSON; nlohmann's type errors count as refused input.
OptionSpec optionFrom(const nlohmann::json& row) {
    const std::string type = row.at("type").get<std::string>();
    const std::string key = row.at("key").get<std::string>();
    const std::string doc = row.value("doc", std::string("an option"));
    OptionSpec spec;
    if (type == "boolean") {
        spec = booleanOption(key, row.value("default", false), doc);
    } else if (type == "integer" || type == "number") {
        const auto make = type == "integer" ? integerOption : numberOption;
        spec = make(key, row.value("unit", std::string()), row.at("min").get<double>(),
                    row.at("max").get<double>(), row.at("default").get<double>(), doc);
    } else {
        throw std::invalid_argument("type");
    }
    if (row.contains("tune")) {
        spec =
            tunable(spec, row.at("tune").at(0).get<double>(), row.at("tune").at(1).get<double>());
    }
    if (row.contains("off")) spec = switchable(spec, row.at("off").get<double>());
    if (row.contains("alternative_to")) {
        spec = alternativeTo(spec, row.at("alternative_to").get<std::string>());
    }
    return spec;
}

}  // namespace

bool scenarioInput(const uint8_t* data, size_t size) {
    try {
        const Scenario scenario = parseScenarioText(textOf(data, size), "fuzz/scenario.json");
        return !scenario.sources.empty();
    } catch (const ScenarioError&) {
        return false;
    }
}

bool gltfInput(const uint8_t* data, size_t size) {
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    GltfSourceSpec spec;
    spec.path = inputFile(binary ? "input.glb" : "input.gltf", textOf(data, size));
    try {
        return !loadGltfSource(spec, 1).objects.empty();
    } catch (const GltfError&) {
        return false;
    }
}

bool viewScriptInput(const uint8_t* data, size_t size) {
    try {
        return !parseViewScript(textOf(data, size), "fuzz/drive.txt").steps.empty();
    } catch (const ScriptError&) {
        return false;
    }
}

bool baselineInput(const uint8_t* data, size_t size) {
    Baseline baseline;
    try {
        baseline = readBaseline(inputFile("input.baseline.json", textOf(data, size)));
    } catch (const BaselineError&) {
        return false;
    }
    const std::string written = baselineJson(baseline);
    try {
        if (baselineJson(readBaseline(inputFile("again.baseline.json", written))) != written) {
            brokenPromise("a baseline written by the program reads back different");
        }
    } catch (const BaselineError& e) {
        brokenPromise(std::string("a baseline written by the program is refused: ") + e.what());
    }
    return true;
}

bool sampleLogInput(const uint8_t* data, size_t size) {
    try {
        const tune::SampleLog log =
            tune::SampleLog::read(inputFile("samples.jsonl", textOf(data, size)));
        (void)log.samples();
        (void)log.referenceSamples();
        (void)log.referenceNoise();
        (void)log.batches();
        (void)log.mismatch(log.settings());
        return true;
    } catch (const tune::TuneInputError&) {
        return false;
    }
}

bool sweepInput(const uint8_t* data, size_t size) {
    try {
        const Sweep sweep = parseSweep(textOf(data, size), cullerRows());
        return !planConfigs(cullerRows(), CullerOptions{}, sweep).empty();
    } catch (const std::invalid_argument&) {
        return false;
    }
}

bool segmentListInput(const uint8_t* data, size_t size) {
    try {
        const std::vector<SegmentSpec> specs = parseSegmentList(textOf(data, size));
        const PlannedSegments plan = planSegments({}, 300, specs, 300, 1.0 / 30.0);
        for (const Segment& s : plan.segments) {
            if (s.end_frame <= s.first_frame || s.end_frame > 300)
                brokenPromise("a placed segment outside the run or without a frame");
        }
        return true;
    } catch (const std::invalid_argument&) {
        return false;
    } catch (const InputError&) {
        return false;
    }
}

bool cullingFileInput(const uint8_t* data, size_t size) {
    registerFuzzPlugin();
    try {
        const CullingFile file = readCullingFile(inputFile("culling.json", textOf(data, size)));
        Scenario scenario;
        applyCullingFile(file, scenario);
        std::string why;
        if (!scenario.culler.isValid(&why))
            brokenPromise("a culling file read gives invalid options: " + why);
        return true;
    } catch (const ScenarioError&) {
        return false;
    }
}

bool pluginDescriptorInput(const uint8_t* data, size_t size) {
    CullerRow traits;
    traits.name = "fuzz-descriptor";
    traits.summary = "a descriptor from the fuzzer";
    traits.factory = [](const CullerContext&) -> std::unique_ptr<Culler> { return nullptr; };
    try {
        const nlohmann::json rows = nlohmann::json::parse(textOf(data, size));
        for (const nlohmann::json& row : rows.at("options"))
            traits.options.push_back(optionFrom(row));
    } catch (const std::exception&) {  // not JSON, or not the rows' shape: nothing to offer
        return false;
    }
    try {
        CullerRegistry().check(traits);
    } catch (const RegistryError&) {
        return false;
    }
    // Accepted: its defaults are valid options, and so is each mechanism switched off.
    OptionValues values(traits.options);
    if (const std::string why = checkOptionValues(traits, values); !why.empty()) {
        brokenPromise("an accepted descriptor's defaults are refused: " + why);
    }
    for (const OptionSpec& spec : traits.options) {
        (void)describeOptionRange(spec);
        (void)formatOptionValue(spec, spec.default_value);
        if (!spec.off_value) continue;
        OptionValues off(traits.options);
        off.setWithAlternatives(spec.key, *spec.off_value);
        if (const std::string why = checkOptionValue(spec, *spec.off_value); !why.empty()) {
            brokenPromise("an accepted descriptor's off value is refused: " + why);
        }
    }
    return true;
}

bool mocrecInput(const uint8_t* data, size_t size) {
    MocFrame frame;
    try {
        frame = parseMocrec(std::span<const uint8_t>(data, size), "fuzz/input.mocrec");
    } catch (const MocrecError&) {
        return false;
    }
    // masked-replay allocates per pixel: an accepted frame must be one its budget holds.
    if (frame.width == 0 || frame.height == 0 ||
        uint64_t{frame.width} * frame.height > kMocrecMaxPixels)
        brokenPromise("an accepted frame past the replay's memory budget");
    auto check = [](const MocBatch& b) {
        if (b.indices.size() % 3 != 0) brokenPromise("a batch with a partial triangle");
        for (const uint32_t i : b.indices) {
            if (i >= b.clip.size()) brokenPromise("an index past its batch's vertices");
        }
        for (const glm::dvec4& c : b.clip) {
            if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) ||
                !std::isfinite(c.w))
                brokenPromise("a clip coordinate that is not finite");
        }
    };
    for (const MocBatch& b : frame.occluders) check(b);
    for (const MocTriangleTest& t : frame.triangle_tests) {
        check(t.batch);
        if (t.occluders_before > frame.occluders.size()) brokenPromise("a test after no occluder");
    }
    for (const MocRectTest& r : frame.rect_tests) {
        if (r.occluders_before > frame.occluders.size()) brokenPromise("a test after no occluder");
    }
    return true;
}

const std::vector<FuzzTarget>& fuzzTargets() {
    static const std::vector<FuzzTarget> targets{
        {"scenario", scenarioInput,
         "the scenario parser (JSON reader, every section, expectations)"},
        {"gltf", gltfInput, "the glTF loading path (tinygltf, accessors, hierarchy, animation)"},
        {"view_script", viewScriptInput, "the viewer's script parser (occsim view --script)"},
        {"baseline", baselineInput, "regression baselines (*.baseline.json), read and rewritten"},
        {"sample_log", sampleLogInput, "the tuner's sample log (samples.jsonl, occtune --resume)"},
        {"sweep", sweepInput, "occsim bench --sweep strings, parsed and planned"},
        {"segments", segmentListInput, "occsim bench --segments strings, parsed and placed"},
        {"culling_file", cullingFileInput, "--culling files, a plugin culler's options included"},
        {"plugin_descriptor", pluginDescriptorInput,
         "a plugin's options descriptor, as registered"},
        {"mocrec", mocrecInput, "Masked Occlusion Culling's recorded frames (.mocrec)"},
    };
    return targets;
}

const FuzzTarget* findFuzzTarget(std::string_view name) {
    for (const FuzzTarget& t : fuzzTargets()) {
        if (t.name == name) return &t;
    }
    return nullptr;
}

}  // namespace occsim::fuzz
