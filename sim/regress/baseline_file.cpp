// A baseline file (<scenario>.baseline.json): read strictly, and written one series per line.
#include <cmath>
#include <fstream>
#include <sstream>
#include <type_traits>

#include "sim/regress/regress.h"
#include "sim/scenario/json_reader.h"

namespace occsim {
namespace {

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw BaselineError(file.string() + ": cannot open the baseline file");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

template <class T>
std::vector<T> readSeries(JsonObjectReader& trace, const char* key, uint32_t frames) {
    const JsonArrayReader array = trace.array(key);
    if (array.size() != frames) {
        trace.fail(key, "expected " + std::to_string(frames) + " values (one per frame), got " +
                            std::to_string(array.size()));
    }
    std::vector<T> values;
    for (size_t i = 0; i < array.size(); ++i) {
        const JsonValueReader v = array.at(i);
        if constexpr (std::is_signed_v<T>) {
            const double d = v.asNumber(NumberRange::atLeast(-1.0));
            if (d != std::floor(d)) v.failExpected("an integer");
            values.push_back(static_cast<T>(d));
        } else {
            values.push_back(static_cast<T>(v.asUnsigned()));
        }
    }
    return values;
}

}  // namespace

Baseline readBaseline(const std::filesystem::path& file) {
    const std::string name = file.string();
    try {
        const Json root = parseStrictJson(readText(file), name);
        JsonObjectReader top(root, "", name);
        if (top.string("format", "") != "occsim-baseline") {
            top.fail("format", "expected \"occsim-baseline\": this is not an occsim baseline file");
        }
        const JsonValueReader version = top.required("version");
        if (!(version.json().is_number_integer() && version.json() == Baseline::kFormatVersion)) {
            throw BaselineError(name + ": /version: baseline format version " +
                                version.json().dump() + "; this program reads version " +
                                std::to_string(Baseline::kFormatVersion) +
                                " (rewrite it with --update)");
        }
        Baseline b;
        b.scenario = top.string("scenario", "");
        b.deterministic_latency =
            static_cast<uint32_t>(top.requiredUnsignedInteger("deterministic_latency"));
        b.frames = static_cast<uint32_t>(top.requiredUnsignedInteger("frames", 1));
        b.backend = top.string("backend", "");
        b.renderer = top.string("renderer", "");
        const JsonValueReader algorithms_value = top.required("algorithms");
        JsonObjectReader algorithms = algorithms_value.asObject();
        for (const auto& item : algorithms_value.json().items()) {
            const std::string algorithm = item.key();
            JsonObjectReader trace = algorithms.required(algorithm).asObject();
            AlgorithmTrace t;
            t.queries = readSeries<uint64_t>(trace, "queries", b.frames);
            t.objects = readSeries<uint64_t>(trace, "objects", b.frames);
            t.error_pixels = readSeries<int64_t>(trace, "error_pixels", b.frames);
            t.missed_objects = readSeries<int64_t>(trace, "missed_objects", b.frames);
            trace.finish();
            b.algorithms[algorithm] = std::move(t);
        }
        algorithms.finish();
        top.finish();
        return b;
    } catch (const ScenarioError& e) {
        throw BaselineError(e.what());
    }
}

std::string baselineJson(const Baseline& b) {
    // One line per series keeps diffs of a baseline readable in review.
    std::ostringstream out;
    out << "{\n  \"format\": \"occsim-baseline\",\n  \"version\": " << Baseline::kFormatVersion
        << ",\n  \"scenario\": " << Json(b.scenario).dump()
        << ",\n  \"deterministic_latency\": " << b.deterministic_latency
        << ",\n  \"frames\": " << b.frames;
    if (!b.backend.empty()) out << ",\n  \"backend\": " << Json(b.backend).dump();
    if (!b.renderer.empty()) out << ",\n  \"renderer\": " << Json(b.renderer).dump();
    out << ",\n  \"algorithms\": {";
    bool first = true;
    for (const auto& [name, t] : b.algorithms) {
        out << (first ? "" : ",") << "\n    " << Json(name).dump()
            << ": {\n      \"queries\": " << Json(t.queries).dump()
            << ",\n      \"objects\": " << Json(t.objects).dump()
            << ",\n      \"error_pixels\": " << Json(t.error_pixels).dump()
            << ",\n      \"missed_objects\": " << Json(t.missed_objects).dump() << "\n    }";
        first = false;
    }
    out << "\n  }\n}\n";
    return out.str();
}

}  // namespace occsim
