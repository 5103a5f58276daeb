#include "tune/tuned_file.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "sim/scenario/culling_file.h"
#include "sim/scenario/option_json.h"

namespace occsim::tune {

std::optional<CostModel> costModelOf(const FrameTimeModel& model) {
    const CostModel c{model.query_ms, model.triangleMs(), model.draw_call_ms};
    // The culler refuses a cost model whose three figures are all 0 (nothing would cost anything).
    if (!c.known()) return std::nullopt;
    return c;
}

void addCostOption(nlohmann::json& culling, const CostModel& model, const std::string& culler) {
    culling["cost_model"] = {{"query_box_ms", model.query_box_ms},
                             {"triangle_ms", model.triangle_ms},
                             {"draw_call_ms", model.draw_call_ms},
                             {"cullers", {culler}}};
}

Setting tunedSetting(const CullerRow& algorithm, const OptionValues& tuned,
                     const FrameTimeModelFit& cost, bool apply_cost_model, std::string* why) {
    Setting setting{"tuned", tuned, std::nullopt};
    why->clear();
    if (!algorithm.cost_model_use || !algorithm.cost_model_use(tuned).wanted) return setting;
    const double share =
        cost.mean_frame_ms > 0.0 ? cost.residual_rms_ms / cost.mean_frame_ms : INFINITY;
    char percent[64];
    std::snprintf(percent, sizeof percent, "%.0f %%", 100.0 * share);
    if (!apply_cost_model) {
        *why = algorithm.name +
               " confirmed and written without the fitted cost model: it calibrates at start-up, "
               "as in every sample (--apply-cost-model confirms it with the fitted one; fit "
               "residual RMS " +
               std::string(percent) + " of the mean frame)";
    } else if (!cost.fit.converged) {
        *why = "the fitted cost model did not converge: " + algorithm.name +
               " confirmed and written without it (it calibrates at start-up)";
    } else if (!(share <= kMaxCostModelResidualShare)) {
        *why = "the fitted cost model explains the frames too poorly to steer " + algorithm.name +
               " (residual RMS " + percent + " of the mean frame, above the " +
               std::to_string(static_cast<int>(100 * kMaxCostModelResidualShare)) +
               " % allowed): confirmed and written without it (it calibrates at start-up)";
    } else if (const std::optional<CostModel> model = costModelOf(cost.model)) {
        setting.cost_model = model;
    } else {
        *why =
            "the fitted cost model is 0 for queries, triangles and draw calls: " + algorithm.name +
            " confirmed and written without it (it is in cost_model.json only)";
    }
    return setting;
}

const Setting& writtenSetting(const Verdict& verdict, const Setting& tuned,
                              const Setting& reference) {
    return verdict.kind == Verdict::Kind::NoChange ? reference : tuned;
}

TunedFile tunedFile(const CullerRow& algorithm, const Setting& setting) {
    // Ordered, so that the file reads in the order of the culler's descriptor.
    nlohmann::ordered_json culling = {{"algorithm", algorithm.name},
                                      {algorithm.name, optionValuesJson(setting.options)}};
    TunedFile file;
    if (setting.cost_model) {
        nlohmann::json cost_option = nlohmann::json::object();
        addCostOption(cost_option, *setting.cost_model, algorithm.name);
        for (const auto& [key, value] : cost_option.items()) culling[key] = value;
        file.has_cost_option = true;
        file.note = "tuned.json carries the fitted culling.cost_model for " + algorithm.name +
                    " only (\"cullers\": [\"" + algorithm.name + "\"]): no other culler reads it";
    }
    // "tuned_for" makes occsim check the file as one culler's setting
    // (sim/scenario/culling_file.h).
    const nlohmann::ordered_json top = {
        {"format_version", 1}, {"tuned_for", algorithm.name}, {"culling", culling}};
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
    const auto scoped = probe.culler.cost_model_of.find(algorithm.name);
    const bool read_cost = scoped != probe.culler.cost_model_of.end();
    const bool cost_reads_back = setting.cost_model
                                     ? read_cost && scoped->second == *setting.cost_model
                                     : !read_cost && !probe.culler.cost_model.known();
    if (probe.algorithm != algorithm.name || !(probe.culler.of(algorithm) == setting.options) ||
        !cost_reads_back) {
        throw std::runtime_error("tuned.json does not read back as the confirmed setting");
    }
    return file;
}

}  // namespace occsim::tune
