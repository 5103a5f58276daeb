#include "tune/tuned_file.h"

#include "culling/algorithms.h"
#include "sim/scenario/culling_file.h"

#include <stdexcept>

namespace occsim::tune {

bool addCostOption(nlohmann::json& culling, const CostModel& model) {
    // The culler refuses a cost model whose three figures are all 0 (nothing would cost anything).
    if (model.query_ms <= 0.0 && model.triangleMs() <= 0.0 && model.draw_ms <= 0.0) return false;
    culling["cost_model"] = {{"query_box_ms", model.query_ms},
                             {"triangle_ms", model.triangleMs()},
                             {"draw_call_ms", model.draw_ms}};
    return true;
}

TunedFile tunedFile(const StatisticalOptions& tuned, const CostModel& cost) {
    // Ordered, so that the file reads in the order a scenario's culling section does.
    nlohmann::ordered_json culling = {{"algorithm", "statistical"},
                              {"statistical",
                               {{"base_time", tuned.base_time_s},
                                {"decay_a", tuned.decay_a},
                                {"decay_b", tuned.decay_b},
                                {"history_length", tuned.history_length},
                                {"max_statistics_age", tuned.max_statistics_age_s},
                                {"queries_before_restart", tuned.queries_before_restart}}}};
    TunedFile file;
    nlohmann::json cost_option = nlohmann::json::object();
    file.has_cost_option = addCostOption(cost_option, cost);
    for (const auto& [key, value] : cost_option.items()) culling[key] = value;
    const nlohmann::ordered_json top = {{"format_version", 1}, {"culling", culling}};
    file.text = top.dump(2) + "\n";

    // Read back from the text as `occsim --culling` will: a file this build refuses is never
    // written.
    Scenario probe;
    try {
        applyCullingFile(CullingFile{"tuned.json", parseStrictJson(file.text, "tuned.json")}, probe);
    } catch (const ScenarioError& e) {
        throw std::runtime_error(std::string("tuned.json would be refused by occsim --culling: ") + e.what());
    }
    if (probe.culler.statistical.base_time_s != tuned.base_time_s || probe.culler.statistical.decay_a != tuned.decay_a ||
        probe.culler.statistical.decay_b != tuned.decay_b) {
        throw std::runtime_error("tuned.json does not read back as the tuned values");
    }
    return file;
}

}  // namespace occsim::tune
