#include "tune/tuned_file.h"

#include <stdexcept>

#include "sim/scenario/culling_file.h"

namespace occsim::tune {

bool addCostOption(nlohmann::json& culling, const FrameTimeModel& model,
                   const std::string& culler) {
    // The culler refuses a cost model whose three figures are all 0 (nothing would cost anything).
    if (model.query_ms <= 0.0 && model.triangleMs() <= 0.0 && model.draw_call_ms <= 0.0)
        return false;
    culling["cost_model"] = {{"query_box_ms", model.query_ms},
                             {"triangle_ms", model.triangleMs()},
                             {"draw_call_ms", model.draw_call_ms},
                             {"cullers", {culler}}};
    return true;
}

TunedFile tunedFile(const AlgorithmTraits& algorithm, const OptionValues& tuned,
                    const FrameTimeModel& cost) {
    // Ordered, so that the file reads in the order of the culler's descriptor.
    nlohmann::ordered_json options = nlohmann::ordered_json::object();
    for (const OptionSpec& spec : tuned.descriptor()) {
        const double v = tuned.number(spec.key);
        if (spec.type == OptionType::Boolean) {
            options[spec.key] = v != 0.0;
        } else if (spec.type == OptionType::Integer) {
            options[spec.key] = static_cast<uint64_t>(v);
        } else {
            options[spec.key] = v;
        }
    }
    nlohmann::ordered_json culling = {{"algorithm", algorithm.name}, {algorithm.name, options}};
    TunedFile file;
    file.weighs_costs = algorithm.cost_model_use && algorithm.cost_model_use(tuned).wanted;
    if (file.weighs_costs) {
        nlohmann::json cost_option = nlohmann::json::object();
        file.has_cost_option = addCostOption(cost_option, cost, algorithm.name);
        for (const auto& [key, value] : cost_option.items()) culling[key] = value;
        if (file.has_cost_option) {
            file.note = "tuned.json carries the fitted culling.cost_model for " + algorithm.name +
                        " only (\"cullers\": [\"" + algorithm.name +
                        "\"]): no other culler reads it";
        }
    }
    const nlohmann::ordered_json top = {{"format_version", 1}, {"culling", culling}};
    file.text = top.dump(2) + "\n";

    // Read back from the text as `occsim --culling` will: a file this build refuses is never
    // written.
    Scenario probe;
    try {
        applyCullingFile(CullingFile{"tuned.json", parseStrictJson(file.text, "tuned.json")},
                         probe);
    } catch (const ScenarioError& e) {
        throw std::runtime_error(std::string("tuned.json would be refused by occsim --culling: ") +
                                 e.what());
    }
    if (probe.algorithm != algorithm.name || !(probe.culler.of(algorithm) == tuned)) {
        throw std::runtime_error("tuned.json does not read back as the tuned values");
    }
    return file;
}

}  // namespace occsim::tune
