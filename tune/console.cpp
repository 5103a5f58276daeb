#include "tune/console.h"

#include <cstdio>

#include "tune/report.h"

namespace occsim::tune {
namespace {

// The tuned values beside the reference's, one parameter a line, and any on a bound.
void printChoice(const TuneResult& r, const CullerRow& algorithm) {
    const std::string ref = referenceName(algorithm);  // "the paper's values", "the defaults"
    std::printf("%s, %s: %zu samples, %s frame-time ratio to %s\n", r.scenario_name.c_str(),
                algorithm.name.c_str(), r.samples.size(), objectiveName(r.options->objective),
                ref.c_str());
    const std::string kept = "  (no effect beyond noise: kept at " + ref + ")";
    for (size_t j = 0; j < r.space.size(); ++j) {
        const TunableParameter& p = r.space.parameters[j];
        std::printf("  %-22s %-9s %-8.4g tuned %-8.4g%s\n", p.name.c_str(),
                    referenceLabel(algorithm).c_str(), p.paper_value, r.tuned_values[j],
                    r.kept_at_paper[j] ? kept.c_str() : "");
    }
    for (const std::string& line : boundWarnings(r)) std::printf("%s\n", line.c_str());
}

void printModels(const TuneResult& r) {
    std::printf(
        "cost model: %.4g ms/query, %.4g ms/1000 triangles, %.4g ms/draw, %.4g ms constant "
        "(residual RMS %.2f ms)\n",
        r.cost.model.query_ms, r.cost.model.kilotriangle_ms, r.cost.model.draw_call_ms,
        r.cost.model.constant_ms, r.cost.residual_rms_ms);
    std::printf(
        "response model: predicted ratio %.3f +/- %.3f at the tuned values; leave-one-out error "
        "%.4f\n",
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

void printFinished(const TuneSession& s, const PlotResult& charts) {
    const TuneResult& r = s.result;
    printChoice(r, *r.space.algorithm);
    printModels(r);
    std::printf("%s\n", costModelLine(r).c_str());
    std::printf("%s", confirmationTable(r).c_str());
    std::printf("%s\n", heldOutLine(r).c_str());
    if (!s.tuned_file.note.empty()) std::printf("%s\n", s.tuned_file.note.c_str());
    if (!charts.ok && !charts.message.empty()) std::printf("%s\n", charts.message.c_str());
    if (const std::string busy = busyMachineNote(r); !busy.empty())
        std::printf("%s\n", busy.c_str());
    std::printf("verdict: %s: %s\n", r.verdict.name(), r.verdict.reason.c_str());
    std::printf("written: %s/{%s,report.md,cost_model.json,samples.jsonl}\n",
                s.out_dir.string().c_str(), r.verdict.fileName());
}

}  // namespace occsim::tune
