// The "culling" section of a scenario: the algorithm, the knobs every query-based culler shares,
// the cost model, and each registered culler's options object under its own name, read through
// its descriptor (occsim/culling/declaration/options.h). A plugin's culler is read exactly as a
// built-in: the same types, ranges and one-line errors at the key's JSON pointer.
#include <cmath>
#include <limits>

#include "occsim/culling/registry/registry.h"
#include "sim/scenario/option_json.h"
#include "sim/scenario/parser_parts.h"

namespace occsim {
namespace {

// A culler's options object: keys it omits keep `defaults` (its descriptor's defaults, or what
// the scenario gave before a --culling file is applied over it).
OptionValues readCullerOptions(JsonObjectReader reader, const CullerRow& culler) {
    OptionValues values(culler.options);
    for (const OptionSpec& spec : culler.options) {
        if (const auto value = reader.optional(spec.key)) {
            values.set(spec.key, readOptionValue(*value, spec));
        }
    }
    reader.finish();
    if (culler.validate) {
        if (const std::string why = culler.validate(values); !why.empty()) reader.failHere(why);
    }
    return values;
}

// What drawing and querying cost (milliseconds); the tuner writes it, or calibration measures it.
// With "cullers": [NAME, ...], the model is for those cullers only (their names into *cullers).
CostModel readCostModel(JsonObjectReader reader, std::vector<std::string>* cullers) {
    CostModel c;
    c.query_box_ms = reader.number("query_box_ms", c.query_box_ms);
    c.triangle_ms = reader.number("triangle_ms", c.triangle_ms);
    c.draw_call_ms = reader.number("draw_call_ms", c.draw_call_ms);
    if (auto names = reader.optionalArray("cullers")) {
        names->requireAtLeast(1, "culler");
        for (size_t i = 0; i < names->size(); ++i)
            cullers->push_back(names->at(i).asEnum(cullerNames()));
    }
    reader.finish();
    std::string why;
    if (!c.isValid(&why)) reader.failHere(why);
    if (!c.known()) reader.failHere("a cost model needs at least one figure > 0 (milliseconds)");
    return c;
}

}  // namespace

void readCulling(JsonObjectReader& top, Scenario& s) {
    auto culling = top.optionalObject("culling");
    if (!culling) return;
    s.algorithm = culling->enumeration("algorithm", cullerNames(), s.algorithm);
    // The approximation knobs, shared by every query-based algorithm (approximation_options.h).
    s.culler.approximation.threshold_pixels = static_cast<uint32_t>(culling->unsignedInteger(
        "threshold_pixels", s.culler.approximation.threshold_pixels, 0, kMaxUint32));
    s.culler.approximation.stale_results =
        culling->boolean("stale_results", s.culler.approximation.stale_results);
    if (auto costs = culling->optionalObject("cost_model")) {
        std::vector<std::string> cullers;
        const CostModel model = readCostModel(std::move(*costs), &cullers);
        if (cullers.empty()) s.culler.cost_model = model;
        for (const std::string& name : cullers)
            s.culler.cost_model_of.insert_or_assign(name, model);
    }
    for (const CullerRow* culler : cullerRows()) {
        if (auto options = culling->optionalObject(culler->name)) {
            s.culler.given.insert_or_assign(culler->name,
                                            readCullerOptions(std::move(*options), *culler));
        }
    }
    culling->finish();
}

}  // namespace occsim
