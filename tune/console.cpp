#include "tune/console.h"

#include <cstdio>
#include <string>

#include "sim/output/console_table.h"
#include "tune/report.h"

namespace occsim::tune {
namespace {

// printf into a string.
template <class... Args>
std::string formatted(const char* format, Args... args) {
    const int n = std::snprintf(nullptr, 0, format, args...);
    std::string out(static_cast<size_t>(n > 0 ? n : 0), '\0');
    std::snprintf(out.data(), out.size() + 1, format, args...);
    return out;
}

// The tuned values beside the reference's, one parameter a line, any on a bound, and the options
// left out of the fit.
std::string choiceText(const TuneResult& r, const CullerRow& algorithm) {
    const std::string ref = referenceName(algorithm);  // "the paper's values", "the defaults"
    std::string out = formatted("%s, %s: %zu samples, %s frame-time ratio to %s\n",
                                r.scenario_name.c_str(), algorithm.name.c_str(), r.samples.size(),
                                objectiveName(r.options->objective), ref.c_str());
    const std::string kept = "  (kept: no effect beyond noise)";
    for (size_t j = 0; j < r.space.size(); ++j) {
        const TunableParameter& p = r.space.parameters[j];
        out += formatted("  %-22s %-9s %-8.4g tuned %-8.4g%s\n", p.name.c_str(),
                         referenceLabel(algorithm).c_str(), p.paper_value, r.tuned_values[j],
                         r.kept_at_paper[j] ? kept.c_str() : "");
    }
    for (const std::string& line : boundWarnings(r)) out += line + "\n";
    for (const std::string& why : r.left_out)
        out += "left out of the fit, kept at " + ref + ": " + why + "\n";
    return out;
}

std::string modelsText(const TuneResult& r) {
    return formatted(
               "cost model: %.4g ms/query, %.4g ms/1000 triangles, %.4g ms/draw, %.4g ms "
               "constant (residual RMS %.2f ms)\n",
               r.cost.model.query_ms, r.cost.model.kilotriangle_ms, r.cost.model.draw_call_ms,
               r.cost.model.constant_ms, r.cost.residual_rms_ms) +
           formatted(
               "response model: predicted ratio %.3f +/- %.3f at the tuned values; leave-one-out "
               "error %.4f\n",
               r.predicted_tuned, r.predicted_tuned_sd, r.response.loo_rms);
}

}  // namespace

void printInterrupted(const TuneSession& s, const TuneOptions& o) {
    std::string resume = o.command_line;
    if (resume.find("--resume") == std::string::npos) resume += " --resume";
    std::fprintf(stderr,
                 "occtune: interrupted %s: %zu of %u samples are in %s (whole); no tuned.json "
                 "written. Resume with: %s\n",
                 s.interrupted_confirming ? "during the confirmation" : "while sampling",
                 s.samples_logged, o.budget, s.log_file.string().c_str(), resume.c_str());
}

void printFitFailed(const TuneSession& s) {
    std::fprintf(stderr,
                 "occtune: the %s model fit did not converge; no tuned.json written. Ceres: %s\n",
                 s.failed_model.c_str(), s.ceres_summary.c_str());
}

// Every line within 100 columns (wrappedText), the confirmation table as it is (it fits).
void printFinished(const TuneSession& s, const PlotResult& charts) {
    const TuneResult& r = s.result;
    std::string out = choiceText(r, *r.space.algorithm) + modelsText(r) + costModelLine(r) + "\n" +
                      confirmationTable(r) + heldOutLine(r) + "\n";
    if (!s.tuned_file.note.empty()) out += s.tuned_file.note + "\n";
    if (!charts.ok && !charts.message.empty()) out += charts.message + "\n";
    if (const std::string busy = busyMachineNote(r); !busy.empty()) out += busy + "\n";
    out += std::string("verdict: ") + r.verdict.name() + ": " + r.verdict.reason + "\n";
    out += "written: " + s.out_dir.string() + "/{" + r.verdict.fileName() +
           ",report.md,cost_model.json,samples.jsonl}\n";
    std::fputs(wrappedText(out).c_str(), stdout);
}

}  // namespace occsim::tune
