#include "tune/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "sim/output/console_table.h"
#include "sim/output/fixed_text.h"
#include "tune/tuned_file.h"

namespace occsim::tune {
namespace {

// occsim::fixed, with "n/a" for a figure that could not be computed (NaN).
std::string fixed(double v, int decimals) {
    return std::isnan(v) ? "n/a" : occsim::fixed(v, decimals);
}

std::string general(double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

std::string percent(double part, double whole) {
    return whole > 0 ? fixed(100.0 * part / whole, 1) + " %" : "n/a";
}

std::string withUnit(const TunableParameter& p, double v) {
    return general(v) + (!p.unit.empty() ? std::string(" ") + p.unit : "");
}

// "the paper's values" for `statistical`, "the defaults" for any other culler; a result without
// a culler (tests of the formatting) says "the reference".
std::string reference(const TuneResult& r) {
    return r.space.algorithm ? referenceName(*r.space.algorithm) : "the reference";
}
std::string referenceShort(const TuneResult& r) {
    return r.space.algorithm ? referenceLabel(*r.space.algorithm) : "ref";
}

// A verdict that does not claim more than the repetitions show.
std::string verdict(const ConfirmationRow& row, const std::string& ref) {
    if (row.tuned_error_pixels > row.paper_error_pixels) {
        return "**the tuned setting showed more error pixels than " + ref + "**";
    }
    if (row.tuned_missed_objects > row.paper_missed_objects) {
        return "**the tuned setting missed more objects than " + ref + "**";
    }
    // The same options and the same cost model (Setting::sameSettingAs), not merely the same
    // option values: a cost model alone changes decisions.
    if (row.same_setting) return "the same setting twice: the spread is the measurement noise";
    if (row.same_decisions)
        return "no change: the same decisions as " + ref + " on every frame (the spread is noise)";
    // Error pixels in both, no more with the tuned values: say so beside the timing verdict.
    const std::string both =
        row.tuned_error_pixels != 0 ? "; error pixels in both, no more with the tuned values" : "";
    if (row.mean_ratio.max < 1.0) return "faster in every repetition" + both;
    if (row.mean_ratio.min > 1.0) return "**slower in every repetition**" + both;
    if (row.mean_ratio.median <= 1.0) {
        return "no worse (median at or below 1; the repetitions span 1)" + both;
    }
    return "within the spread of the repetitions, median above 1" + both;
}

void samplesTable(std::ostringstream& out, const TuneResult& r) {
    out << "| # | batch | from | ";
    for (const TunableParameter& p : r.space.parameters) out << p.name << " | ";
    out << "mean ratio | p95 ratio | error px |\n|---|---|---|";
    for (size_t j = 0; j < r.space.size(); ++j) out << "---|";
    out << "---|---|---|\n";
    for (size_t i = 0; i < r.samples.size(); ++i) {
        const Sample& s = r.samples[i];
        out << "| " << i << " | " << s.run->batch << " | "
            << (i < r.initial_samples ? "design" : "adaptive") << " | ";
        for (double v : s.run->values) out << general(v) << " | ";
        out << fixed(s.ratio_mean, 3) << " | " << fixed(s.ratio_p95, 3) << " | "
            << s.run->error_pixels << " |\n";
    }
}

}  // namespace

std::vector<std::string> boundWarnings(const TuneResult& r) {
    std::vector<std::string> lines;
    for (size_t j = 0; j < r.space.size() && j < r.tuned_values.size(); ++j) {
        // A value kept at the reference that --bounds excluded: the result lies outside the range
        // the user asked to search, which needs saying.
        const TunableParameter& p = r.space.parameters[j];
        const Bounds& b = r.space.bounds[j];
        const double v = r.tuned_values[j];
        if (j < r.kept_at_paper.size() && r.kept_at_paper[j] && (v < b.lo || v > b.hi)) {
            lines.push_back(p.name + " = " + withUnit(p, v) + " (" + reference(r) +
                            ") lies outside its search range [" + general(b.lo) + ", " +
                            general(b.hi) +
                            "]: kept there because the samples showed no effect of it beyond "
                            "noise, so no value in the range was shown to be better");
        }
    }
    for (size_t j = 0; j < r.space.size() && j < r.bounds_hit.size(); ++j) {
        if (r.bounds_hit[j].empty()) continue;
        const TunableParameter& p = r.space.parameters[j];
        const Bounds& b = r.space.bounds[j];
        const double width = b.hi - b.lo;
        const bool lower = r.bounds_hit[j] == "lower";
        // Suggest a box twice as wide on that side, within the option's valid range.
        const double lo = lower ? std::max(p.min, b.lo - width) : b.lo;
        const double hi = lower ? b.hi : std::min(p.max, b.hi + width);
        std::string line = p.name + " = " + withUnit(p, r.tuned_values[j]) + " sits on the " +
                           r.bounds_hit[j] + " bound of its search range [" + general(b.lo) + ", " +
                           general(b.hi) + "]: the best value may lie beyond it";
        if ((lower && lo < b.lo) || (!lower && hi > b.hi)) {
            line += "; widen it, e.g. --bounds " + p.name + "=" + general(lo) + ":" + general(hi);
        } else {
            line += " (the end of the option's valid range)";
        }
        lines.push_back(line);
    }
    return lines;
}

const char* objectiveName(Objective objective) {
    return objective == Objective::Mean ? "mean" : "p95";
}

std::string formatSpread(const Spread& s) {
    return fixed(s.median, 3) + " [" + fixed(s.min, 3) + "-" + fixed(s.max, 3) + "]";
}

std::string costModelLine(const TuneResult& r) {
    const std::string name = r.space.algorithm ? r.space.algorithm->name : "the culler";
    if (r.cost_model_applied) {
        return "The tuned setting includes the fitted cost model, for " + name +
               " alone (residual RMS " + percent(r.cost.residual_rms_ms, r.cost.mean_frame_ms) +
               " of the mean frame, at most " +
               std::to_string(static_cast<int>(100 * kMaxCostModelResidualShare)) +
               " % allowed): the confirmation ran with it, and tuned.json carries it unless the "
               "verdict is \"no change\".";
    }
    if (!r.cost_model_note.empty()) return r.cost_model_note + ".";
    return name +
           " weighs no costs with these options: the fitted cost model is in "
           "cost_model.json only.";
}

std::string confirmationTable(const TuneResult& r) {
    // At most 100 columns on a console: ms and the error counts as "tuned/reference" pairs, the
    // frames with their repetitions; report.md has every figure in columns of its own.
    const std::string ref = referenceShort(r);  // "paper", "default" ("ref" without a culler)
    const auto pair = [](long long tuned, long long reference) {
        return std::to_string(tuned) + "/" + std::to_string(reference);
    };
    std::vector<std::vector<std::string>> rows = {{"variant", "frames", "mean ratio [min-max]",
                                                   "p95 ratio", "ms", "err px", "tie px",
                                                   "missed"}};
    for (const ConfirmationRow& c : r.confirmation) {
        rows.push_back({c.variant, std::to_string(c.frames) + "x" + std::to_string(c.repetitions),
                        formatSpread(c.mean_ratio), fixed(c.p95_ratio.median, 3),
                        fixed(c.tuned_mean_ms, 2) + "/" + fixed(c.paper_mean_ms, 2),
                        pair(c.tuned_error_pixels, c.paper_error_pixels),
                        pair(c.tuned_tie_pixels, c.paper_tie_pixels),
                        pair(c.tuned_missed_objects, c.paper_missed_objects)});
    }
    std::ostringstream out;
    out << alignColumns(rows, {0, 2});
    out << "ratios tuned / " << ref << ": median [min-max] of the runs; frames x repetitions;\n"
        << "ms, err px, tie px, missed: tuned/" << ref << "\n";
    return out.str();
}

std::string busyMachineNote(const TuneResult& r) {
    if (r.busy_runs == 0) return "";
    return "busy machine: " + std::to_string(r.busy_runs) + " of " + std::to_string(r.runs) +
           " runs of this session ran beside other work (load average above the " +
           std::to_string(r.hardware_threads) +
           " hardware threads before a run, or above twice that after it); these timings are not "
           "results";
}

std::string heldOutLine(const TuneResult& r) {
    const std::string seed = "held out: seed " + std::to_string(r.held_out_seed);
    if (r.held_out_changes == "nothing") {
        return seed +
               " changes nothing in this scene (no generator lays it out, no mover or animation "
               "phase is seeded), so the held-out run repeats the fitted frames: a second "
               "measurement of them, not another scene.";
    }
    return seed + " changes " + r.held_out_changes +
           "; the camera path stays: the fit never saw those frames.";
}

namespace {

// What was tuned on what, how it was measured, and how noisy the measurements were.
void headerSection(std::ostringstream& out, const TuneResult& r) {
    const TuneOptions& o = *r.options;
    const char* objective = objectiveName(r.options->objective);
    const std::string ref = reference(r);
    out << "# Tuning the " << r.space.algorithm->name << " culler on " << r.scenario_name << "\n\n"
        << "Command: `" << o.command_line << "`\n\n"
        << "- Scenario: `" << r.scenario_file << "` (seed " << r.scenario_seed << "), " << r.frames
        << " frames (" << (r.frames - r.warmup_frames) << " timed after " << r.warmup_frames
        << " warm-up), " << r.objects << " objects, " << r.triangles << " triangles\n"
        << "- Machine: " << r.renderer << ", " << r.hardware_threads
        << " hardware threads; measured mode (query "
        << "results ready when the GPU says so), error measured against ground truth\n"
        << "- Objective: the " << objective << " frame time of a sample over the " << objective
        << " frame time of " << ref
        << ", both from the same run (interleaved frame by "
           "frame)\n"
        << "- Samples: " << r.samples.size() << " (" << r.initial_samples
        << " from a seeded Latin hypercube, seed " << o.seed
        << "; the rest where the fitted response was uncertain or promising), in "
        << r.log->batches() << " runs, each beside two reference runs of " << ref << "\n"
        << "- Measurement noise: one run's mean frame time varies by "
        << fixed(100.0 * r.reference_noise, 1)
        << " % (standard deviation, from the two reference runs of every batch, which differ in "
           "nothing but "
           "noise); a sample's ratio carries that noise and a share of its batch's references'\n"
        << "- Error pixels over every frame of every sample and reference: "
        << r.sample_error_pixels
        << (r.sample_error_pixels == 0 ? " (the culler is conservative: zero expected)"
                                       : " (**zero expected**)")
        << "\n";
    for (const std::string& why : r.left_out)
        out << "- Left out of the fit, kept at " << ref << ": " << why << "\n";
    out << "\n";
    if (const std::string busy = busyMachineNote(r); !busy.empty())
        out << "**" << busy << ".**\n\n";
}

// The tuned values beside the reference values, what the model predicts of them, and what it
// dropped.
void choiceSection(std::ostringstream& out, const TuneResult& r) {
    const char* objective = objectiveName(r.options->objective);
    const std::string ref = reference(r);
    out << "## Choice\n\n| parameter | " << referenceShort(r)
        << " | tuned | bounds | |\n|---|---|---|---|---|\n";
    for (size_t j = 0; j < r.space.size(); ++j) {
        const TunableParameter& p = r.space.parameters[j];
        out << "| " << p.name << " | " << withUnit(p, p.paper_value) << " | "
            << withUnit(p, r.tuned_values[j]) << " | " << general(r.space.bounds[j].lo) << " to "
            << general(r.space.bounds[j].hi) << " | "
            << (r.kept_at_paper[j] ? "no effect beyond noise: kept at " + ref
                                   : std::string("tuned"))
            << " |\n";
    }
    for (const std::string& line : boundWarnings(r)) out << "\n**" << line << "**\n";
    out << "\nPredicted " << objective << " ratio to " << ref << ": " << fixed(r.predicted_tuned, 3)
        << " +/- " << fixed(r.predicted_tuned_sd, 3) << " at the tuned values (the model gives "
        << fixed(r.predicted_paper, 3) << " at " << ref << " themselves).\n";
    if (!r.dropped.empty()) {
        out << "\nParameters this scene does not exercise: ";
        for (size_t k = 0; k < r.dropped.size(); ++k)
            out << (k ? ", " : "") << r.space.parameters[r.dropped[k]].name;
        out << ". Without their terms the leave-one-out prediction error stays within one standard "
               "error of the "
               "lowest seen ("
            << fixed(r.full_model_loo_rms, 4) << " with every parameter, "
            << fixed(r.response.loo_rms, 4)
            << " without them): the samples show no effect of them beyond their noise, so they "
               "stay at "
            << ref << ".\n";
    }
}

// The confirmation table and the verdict.
void confirmationSection(std::ostringstream& out, const TuneResult& r) {
    const TuneOptions& o = *r.options;
    const std::string ref = reference(r);
    const std::string ref_short = referenceShort(r);
    out << "\n## Confirmation\n\nThe tuned setting against " << ref
        << ", interleaved frame by frame in one run, " << o.repetitions
        << " repetitions; a ratio below 1 means the tuned values are faster. The held-out variant "
        << "is the same scenario with another seed. " << heldOutLine(r) << "\n\n"
        << "| variant | seed | frames | mean ratio, median [min-max] | p95 ratio, median [min-max] "
           "| tuned ms | "
        << ref_short << " ms | queries/frame tuned / " << ref_short << " | objects/frame tuned / "
        << ref_short << " | error px tuned / " << ref_short << " | tie px tuned / " << ref_short
        << " | missed objects tuned / " << ref_short << " | verdict |\n"
        << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const ConfirmationRow& c : r.confirmation) {
        out << "| " << c.variant << " | " << c.seed << " | " << c.frames << " | "
            << formatSpread(c.mean_ratio) << " | " << formatSpread(c.p95_ratio) << " | "
            << fixed(c.tuned_mean_ms, 2) << " | " << fixed(c.paper_mean_ms, 2) << " | "
            << fixed(c.tuned_queries, 1) << " / " << fixed(c.paper_queries, 1) << " | "
            << fixed(c.tuned_objects, 1) << " / " << fixed(c.paper_objects, 1) << " | "
            << c.tuned_error_pixels << " / " << c.paper_error_pixels << " | " << c.tuned_tie_pixels
            << " / " << c.paper_tie_pixels << " | " << c.tuned_missed_objects << " / "
            << c.paper_missed_objects << " | " << verdict(c, ref) << " |\n";
    }

    out << "\n" << costModelLine(r) << "\n";
    out << "\n**Verdict: " << r.verdict.name() << "**: " << r.verdict.reason << " (written as `"
        << r.verdict.fileName() << "`).\n";
}

// The frame-time model's coefficients and how well it fits.
void costModelSection(std::ostringstream& out, const TuneResult& r) {
    const FrameTimeModel& m = r.cost.model;
    out << "\n## Fit quality\n\n### Cost model (per frame)\n\n"
        << "frame_ms = constant + query_ms * queries + kilotriangle_ms * triangles/1000 + draw_ms "
           "* objects drawn + "
           "wait_factor * wait_ms, fitted with Ceres (every coefficient >= 0; loss: "
        << r.cost.fit.loss << ") over " << r.cost.frames << " timed frames of " << r.cost.groups
        << " runs.\n\n"
        << "| term | coefficient | approx. standard error |\n|---|---|---|\n"
        << "| constant (ms) | " << general(m.constant_ms) << " | "
        << general(r.cost.standard_error[0]) << " |\n"
        << "| per query (ms) | " << general(m.query_ms) << " | "
        << general(r.cost.standard_error[1]) << " |\n"
        << "| per 1000 triangles (ms) | " << general(m.kilotriangle_ms) << " | "
        << general(r.cost.standard_error[2]) << " |\n"
        << "| per draw call (ms) | " << general(m.draw_call_ms) << " | "
        << general(r.cost.standard_error[3]) << " |\n"
        << "| per waited ms | " << general(m.wait_factor) << " | "
        << general(r.cost.standard_error[4]) << " |\n\n"
        << "- Residual RMS: " << fixed(r.cost.residual_rms_ms, 2) << " ms ("
        << percent(r.cost.residual_rms_ms, r.cost.mean_frame_ms) << " of the mean frame, "
        << fixed(r.cost.mean_frame_ms, 2) << " ms)\n"
        << "- Prediction error on runs left out of the fit (5 folds of whole runs): "
        << fixed(r.cost.heldout_rms_ms, 2) << " ms ("
        << percent(r.cost.heldout_rms_ms, r.cost.mean_frame_ms) << ")\n"
        << "- Ceres: " << r.cost.fit.ceres_summary << "\n\n";
}

// The response model's terms and how well it predicts.
void responseModelSection(std::ostringstream& out, const TuneResult& r) {
    const char* objective = objectiveName(r.options->objective);
    out << "### Response model (" << objective << " ratio against the tuned parameters)\n\n"
        << "A quadratic in the normalised parameters (z = 2x - 1 over the bounds) of the parameters kept ("
        << (r.response.model.active.empty() ? std::string("none: a constant") : [&] {
               std::string s;
               for (size_t j : r.response.model.active) s += (s.empty() ? "" : ", ") + std::string(r.space.parameters[j].name);
               return s;
           }())
        << "), fitted with Ceres (" << r.response.fit.loss << ") over " << r.response.samples
        << " runs: the samples, and the reference runs at " << reference(r) << " (each as a ratio to its batch's "
           "references), which anchor the model there.\n\n"
        << "- Residual RMS: " << fixed(r.response.residual_rms, 4) << "\n"
        << "- Leave-one-out prediction error (each sample predicted by a fit without it): " << fixed(r.response.loo_rms, 4)
        << "\n- Coefficients:";
    for (Eigen::Index k = 0; k < r.response.model.coefficients.size(); ++k)
        out << " " << general(r.response.model.coefficients[k]);
    out << "\n- Ceres: " << r.response.fit.ceres_summary << "\n\n## Samples\n\n";
    samplesTable(out, r);
}

// The pictures written, or why there are none.
void chartsSection(std::ostringstream& out, const TuneResult& r) {
    out << "\n## Charts\n\n";
    bool any = false;
    for (const std::string& f : r.files) {
        if (f.size() > 4 && f.compare(f.size() - 4, 4, ".png") == 0) {
            out << "![" << f << "](" << f << ")\n\n";
            any = true;
        }
    }
    if (!any) out << (r.charts_message.empty() ? "none" : r.charts_message) << "\n";
}

}  // namespace

std::string reportMarkdown(const TuneResult& r) {
    std::ostringstream out;
    headerSection(out, r);
    choiceSection(out, r);
    confirmationSection(out, r);
    costModelSection(out, r);
    responseModelSection(out, r);
    chartsSection(out, r);
    return out.str();
}

}  // namespace occsim::tune
