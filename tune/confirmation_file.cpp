#include "tune/confirmation_file.h"

#include <nlohmann/json.hpp>

namespace occsim::tune {
namespace {

nlohmann::ordered_json spreadJson(const Spread& s) {
    return {{"median", s.median}, {"min", s.min}, {"max", s.max}};
}

nlohmann::ordered_json variantJson(const ConfirmationRow& row) {
    return {{"variant", row.variant},
            {"seed", row.seed},
            {"frames", row.frames},
            {"repetitions", row.repetitions},
            {"mean_ratio", spreadJson(row.mean_ratio)},
            {"p95_ratio", spreadJson(row.p95_ratio)},
            {"tuned_mean_ms", row.tuned_mean_ms},
            {"reference_mean_ms", row.paper_mean_ms},
            {"tuned_queries", row.tuned_queries},
            {"reference_queries", row.paper_queries},
            {"tuned_objects", row.tuned_objects},
            {"reference_objects", row.paper_objects},
            {"tuned_error_pixels", row.tuned_error_pixels},
            {"reference_error_pixels", row.paper_error_pixels},
            {"tuned_missed_objects", row.tuned_missed_objects},
            {"reference_missed_objects", row.paper_missed_objects},
            {"same_decisions", row.same_decisions},
            {"same_setting", row.same_setting},
            {"renderer", row.renderer}};
}

}  // namespace

std::string confirmationJson(const TuneResult& r) {
    nlohmann::ordered_json parameters = nlohmann::ordered_json::array();
    for (size_t j = 0; j < r.space.size(); ++j) {
        const TunableParameter& p = r.space.parameters[j];
        parameters.push_back(
            {{"name", p.name},
             {"reference", p.paper_value},
             {"tuned", j < r.tuned_values.size() ? r.tuned_values[j] : p.paper_value},
             {"kept_at_reference", j < r.kept_at_paper.size() && r.kept_at_paper[j]},
             {"bound_hit", j < r.bounds_hit.size() ? r.bounds_hit[j] : ""},
             {"search_lo", r.space.bounds[j].lo},
             {"search_hi", r.space.bounds[j].hi}});
    }
    nlohmann::ordered_json variants = nlohmann::ordered_json::array();
    for (const ConfirmationRow& row : r.confirmation) variants.push_back(variantJson(row));
    const nlohmann::ordered_json j = {{"format_version", 1},
                                      {"culler", r.space.algorithm ? r.space.algorithm->name : ""},
                                      {"scenario", r.scenario_name},
                                      {"scenario_file", r.scenario_file},
                                      {"verdict", r.verdict.name()},
                                      {"reason", r.verdict.reason},
                                      {"samples", r.samples.size()},
                                      {"reference_noise", r.reference_noise},
                                      {"cost_model_applied", r.cost_model_applied},
                                      {"cost_model_note", r.cost_model_note},
                                      {"parameters", parameters},
                                      {"variants", variants}};
    return j.dump(2) + "\n";
}

}  // namespace occsim::tune
